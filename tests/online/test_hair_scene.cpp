// The scene assembly of online/scene/hair_scene.h: a HairScene draws what a ShellRenderer assembled by hand from the
// same inputs draws, frames its camera as SceneFraming says, and refuses an eye inside the hair.
#include <gtest/gtest.h>

#include <unistd.h>

#include "models/core/error.h"
#include "models/core/progress.h"
#include "online/scene/hair_scene.h"
#include "online/scene/cook.h"
#include "tests/online/shell_test_scene.h"

namespace coif {
namespace {

// A small database file for the scene to open (HairScene opens by path); built once per test binary.
const std::filesystem::path& test_db_file() {
    static const std::filesystem::path path = [] {
        const auto p = std::filesystem::temp_directory_path() / ("coif-hair-scene-test-" + std::to_string(::getpid()) + ".db");
        Progress::set_quiet(true);
        BuildOptions b;
        b.params.sectors = 40;
        b.threads = 2;
        build_database(b, p);
        return p;
    }();
    return path;
}

struct RemoveTestDb : ::testing::Environment {
    void TearDown() override {
        std::error_code ec;
        std::filesystem::remove(std::filesystem::temp_directory_path() /
                                    ("coif-hair-scene-test-" + std::to_string(::getpid()) + ".db"),
                                ec);
    }
};
const auto* const kRemoveTestDb = ::testing::AddGlobalTestEnvironment(new RemoveTestDb);

gl::HairSceneDesc desc() {
    gl::HairSceneDesc d;
    d.style = test::one_cluster_style();
    d.lights = test::two_lights();
    d.lights_label = "two test lights";
    d.database = test_db_file();
    d.framing.view.width = 64;
    d.framing.view.height = 48;
    d.framing.view.azimuth = 0.3f;
    d.framing.view.elevation = 0.2f;
    return d;
}

TEST(HairScene, DrawsWhatTheRendererAssembledByHandDraws) {
    gl::HairScene scene(desc());
    EXPECT_EQ(scene.lights.size(), 2u);
    EXPECT_EQ(scene.lights_label, "two test lights");
    ASSERT_TRUE(scene.db);
    EXPECT_EQ(scene.db->path(), test_db_file());
    gl::ShellSettings settings;
    settings.samples = 1;
    const Image a = scene.renderer->render(scene.camera, settings);

    Strands sampled;
    gl::ShellRenderer by_hand(cook_shells(scene.style, *scene.satf, style_orientation(scene.style), 0, &sampled));
    by_hand.set_lights(scene.lights);
    const Camera camera = desc().framing.camera_for(std::move(sampled));
    EXPECT_EQ(camera.eye, scene.camera.eye);
    EXPECT_EQ(camera.target, scene.camera.target);
    const Image b = by_hand.render(camera, settings);
    ASSERT_EQ(a.pixels.size(), b.pixels.size());
    EXPECT_EQ(a.pixels, b.pixels);  // the same inputs, the same GPU: the same image, bit for bit

    // view_of: another style, framed by its own strands, shares the scene's index and lights.
    const gl::ShellView other = scene.view_of(test::one_cluster_style(), desc().framing, 0);
    EXPECT_EQ(other.camera.eye, scene.camera.eye);
}

TEST(HairScene, FramingBoxOverridesTheSampledStrands) {
    gl::SceneFraming f;
    f.box = std::pair{glm::vec3(-1.0f), glm::vec3(1.0f)};
    const Camera c = f.camera_for(Strands{});
    EXPECT_EQ(c.target, glm::vec3(0.0f));
    EXPECT_EQ(c.eye, f.view.around(glm::vec3(-1.0f), glm::vec3(1.0f)).eye);
}

TEST(HairScene, RefusesAnEyeInsideTheHair) {
    gl::HairSceneDesc d = desc();
    // A box a hundredth of a centimetre wide in the middle of the 10 cm cluster: the orbit's eye lands inside it.
    d.framing.box = std::pair{glm::vec3(-0.005f, -5.005f, -0.005f), glm::vec3(0.005f, -4.995f, 0.005f)};
    try {
        gl::HairScene scene(std::move(d));
        FAIL() << "an eye inside the hair was accepted";
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("inside the hair"), std::string::npos) << e.what();
    }
}

}  // namespace
}  // namespace coif
