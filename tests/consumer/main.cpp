// Loads a cooked hair asset with the installed runtime and draws it offscreen (EGL): the hair must show.
//   coif_consumer hair.coif out.ppm
#include <coif/coif.h>

#include <cmath>
#include <cstdio>
#include <fstream>

int main(int argc, char** argv) {
    if (argc != 3) {
        std::fprintf(stderr, "usage: coif_consumer HAIR.coif OUT.ppm\n");
        return 2;
    }
    try {
        auto context = coif::gl::Context::headless();
        coif::gl::ShellRenderer hair(coif::read_hair_asset(argv[1]));
        coif::SrbfLight lights[2];
        lights[0].L = glm::vec3(20.0f);  // a key light above and in front
        lights[0].omega = glm::normalize(glm::vec3(0.3f, 0.8f, 0.5f));
        lights[0].lambda = 0.5f;
        lights[1].L = glm::vec3(2.0f);   // a broad fill from everywhere above
        lights[1].omega = glm::vec3(0.0f, 1.0f, 0.0f);
        lights[1].lambda = 2.0f;
        hair.set_lights(lights);
        const coif::Camera camera = coif::Camera::orbit(hair.bounds_min(), hair.bounds_max(), 0.0f, 0.1f, 96, 64);
        coif::gl::ShellSettings settings;
        settings.samples = 1;
        settings.background = glm::vec3(0.0f);
        const coif::Image image = hair.render(camera, settings);
        std::size_t lit = 0;
        std::ofstream out(argv[2], std::ios::binary);
        out << "P6\n" << image.width << " " << image.height << "\n255\n";
        for (int i = 0; i < image.width * image.height; ++i) {
            float luminance = 0;
            for (int c = 0; c < 3; ++c) {
                const float v = image.pixels[static_cast<std::size_t>(i) * 4 + c];
                luminance += v / 3;
                out.put(static_cast<char>(std::lround(255.0f * std::pow(std::min(std::max(v, 0.0f), 1.0f), 1.0f / 2.2f))));
            }
            lit += luminance > 0.01f;
        }
        std::printf("coif_consumer: %zu clusters, %zu of the database's %zu records; %zu of %d pixels show lit hair on %s\n",
                    hair.stats().clusters, hair.stats().records, hair.stats().database_records, lit,
                    image.width * image.height, context->renderer().c_str());
        // Against a black background, the framed hair (about a sixth of the image at this distance) must show.
        if (lit < static_cast<std::size_t>(image.width * image.height) / 20) {
            std::fprintf(stderr, "coif_consumer: the hair does not show\n");
            return 1;
        }
    } catch (const coif::Error& e) {
        std::fprintf(stderr, "coif_consumer: %s\n", e.what());
        return 1;
    }
    return 0;
}
