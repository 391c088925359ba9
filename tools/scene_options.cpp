#include "tools/scene_options.h"

#include "models/core/error.h"
#include "models/style_strands.h"
#include "tools/assets.h"

namespace coif::cli {

// Largest image side the commands accept (the GL target may allow less; it is checked too).
constexpr int kMaxRenderSide = 16384;

HairStyle load_style(const std::string& path) {
    if (path == kDefaultStyleName) {
        constexpr const char* kAsset = "default_style.json";
        const std::vector<std::byte> bytes = asset_bytes(kAsset);
        return parse_style(std::string_view(reinterpret_cast<const char*>(bytes.data()), bytes.size()),
                           std::string("<embedded ") + kAsset + ">");
    }
    return read_style(path);
}

void SceneOptions::add_to(CLI::App* app) {
    app->add_option("--style", style, "Cluster hairstyle (JSON) to draw, or @default for the embedded one");
    app->add_option("--strands", strands, "Draw this strand file (.hair or .data) instead of a style");
    app->add_option("--width", width, "Image width in pixels")->check(CLI::Range(1, kMaxRenderSide));
    app->add_option("--height", height, "Image height in pixels")->check(CLI::Range(1, kMaxRenderSide));
    app->add_option("--azimuth", azimuth_deg, "Camera azimuth about +y in degrees, 0 = looking from +z");
    app->add_option("--elevation", elevation_deg, "Camera elevation in degrees above the horizontal")->check(CLI::Range(-89.0, 89.0));
    app->add_option("--fov", fov_deg, "Vertical field of view in degrees")->check(CLI::Range(1.0, 150.0));
    app->add_flag("--keep-axes", keep_axes, "Keep the file's axes (by default a model whose hair hangs along -x or -z is turned y-up)");
    app->add_option("--frame-strands", frame_strands,
                    "Frame the camera on this strand file (oriented as --strands) instead of what is drawn: lines up images "
                    "of different geometry of the same hair, e.g. a style fitted to the file and the file itself");
}

Strands SceneOptions::load_strands(std::string* label) const {
    if (label)
        *label = !strands.empty() ? strands
               : style == kDefaultStyleName ? "strands sampled from the embedded default style (harolongo, 64 clusters)"
                                            : "strands sampled from " + style;
    return oriented(strands.empty() ? sample_strands(load_style(style), StrandSampling{}) : read_strands(strands));
}

Strands SceneOptions::oriented(Strands s) const {
    if (!keep_axes) {
        const glm::mat3 r = hang_axis_rotation(strand_stats(s));
        for (auto& p : s.points) p = r * p;
    }
    return s;
}

std::pair<glm::vec3, glm::vec3> SceneOptions::frame_box(const Strands& drawn) const {
    const StrandStats st = frame_strands.empty() ? strand_stats(drawn) : strand_stats(oriented(read_strands(frame_strands)));
    return {glm::vec3(st.bbox_min), glm::vec3(st.bbox_max)};
}

Camera SceneOptions::camera_around(const std::pair<glm::vec3, glm::vec3>& box) const {
    return Camera::orbit(box.first, box.second, static_cast<float>(radians(azimuth_deg)), static_cast<float>(radians(elevation_deg)),
                         width, height, static_cast<float>(radians(fov_deg)));
}

}  // namespace coif::cli
