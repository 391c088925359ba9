#include "online/window/viewer.h"

#include <GLFW/glfw3.h>
#include <glm/gtc/matrix_transform.hpp>
#include <imgui.h>
#include <algorithm>
#include <atomic>
#include <chrono>
#include <functional>
#include <future>
#include <cmath>
#include <cstdio>
#include <memory>
#include <string>

#include "models/absorption_map.h"
#include "models/core/error.h"
#include "models/core/image.h"
#include "models/core/log.h"
#include "models/core/units.h"
#include "offline/srbf_fit.h"
#include "offline/srbf_lights.h"
#include "online/gl.h"
#include "online/lighting_uniforms.h"
#include "online/shell_renderer.h"
#include "models/style_edit.h"
#include "online/shells/authoring.h"
#include "online/shells/painting.h"
#include "online/window/panel.h"
#include "online/window/window.h"
#include "shaders/hair_parameters.h"

namespace coif::gl {

Camera ViewerCamera::camera(const OrbitView& base, glm::vec3 lo, glm::vec3 hi, int width, int height) const {
    OrbitView v = base;
    v.azimuth = static_cast<float>(azimuth);
    v.elevation = static_cast<float>(elevation);
    v.width = width;
    v.height = height;
    Camera c = v.around(lo, hi);
    if (zoom == 1.0 && pan == glm::dvec2(0.0)) return c;  // coif render's camera, bit for bit
    const glm::vec3 back = c.eye - c.target;
    const float distance = glm::length(back);
    // Pan in the view plane, in framed heights (the height the field of view spans at the target).
    const glm::vec3 forward = -back / distance;
    const glm::vec3 right = glm::normalize(glm::cross(forward, c.up)), up = glm::cross(right, forward);
    const float framed_height = 2.0f * distance * std::tan(0.5f * c.fov_y);
    const glm::vec3 shift = framed_height * (float(pan.x) * right + float(pan.y) * up);
    c.target += shift;
    c.eye = c.target + float(zoom) * back;
    c.near_plane *= float(zoom);
    c.far_plane *= float(zoom);
    return c;
}

namespace {

using Clock = std::chrono::steady_clock;

// Orbit per pixel of mouse drag, and the elevation's limit (short of the poles, where the y-up camera turns over).
const double kDragRadiansPerPixel = glm::radians(0.4);
const double kMaxElevation = glm::radians(89.0);
// Each wheel step moves the eye 10 % nearer (or farther), within [0.1, 10] times the framing distance.
constexpr double kZoomPerStep = 0.9, kMinZoom = 0.1, kMaxZoom = 10.0;
constexpr float kExposureStep = 1.0f / 3.0f;  // stops per + / − key
constexpr int kDragDivisor = 2;                // the frame's size divisor while the camera or a control point is dragged
constexpr float kPanelWidth = 300.0f, kPanelLabels = 130.0f;  // pixels: the panel, and its labels' column
constexpr int kRefineGrid = 2;      // still: 2 × 2 shifted frames averaged (coif render --samples 4)
constexpr float kHandleRadius = 5.0f;  // pixels: a control point's handle

struct Input {
    double scroll = 0;                 // wheel steps since the last frame
    std::vector<int> keys;             // keys pressed since the last frame
};

// A fit running beside the viewer (the panel's "fit"): the frames go on, and its lights swap in when done. The
// future is the last member, so that destroying a job first waits for the fit that reports into `iteration`.
struct LightsJob {
    std::atomic<int> iteration{0};
    std::string label;
    Clock::time_point start = Clock::now();
    std::future<std::vector<SrbfLight>> lights;
};

// The lights of a map fitted with `count` lights as `coif render --env MAP` fits its 40 (SrbfFitSettings' defaults).
SrbfFitSettings fit_settings(int count) {
    SrbfFitSettings fs;
    fs.lights = count;
    return fs;
}

// The viewer's state and its GL resources, in the window's context.
class Viewer {
public:
    explicit Viewer(ViewerOptions& o)
        : o_(o),
          settings_(o.settings),
          exposure_(o.exposure),
          environment_(o.environment),
          window_(o.view.width, o.view.height, "coif view"),
          authoring_(o.scene.cooked ? std::nullopt : std::optional<HairStyle>(o.scene.style), o.absorption),
          lighting_rows_(o.scene.lighting_rows),
          scene_(scene_desc(o, &cook_cache_)),
          background_({"shaders/gl/fullscreen.vert", "shaders/gl/viewer_background.frag"}),
          present_({"shaders/gl/fullscreen.vert", "shaders/gl/viewer_present.frag"}),
          copy_({"shaders/gl/fullscreen.vert", "shaders/gl/copy_texture.frag"}),
          empty_vao_(make_vertex_array()) {
        camera_.azimuth = o.view.azimuth;
        camera_.elevation = o.view.elevation;
        rotation_deg_ = o.rotate_lights_deg;
        unrotated_ = scene_.lights;
        environment_label_ = scene_.lights_label;
        set_lights();
        std::error_code ec;
        if (!o.maps_folder.empty())
            for (const auto& e : std::filesystem::directory_iterator(o.maps_folder, ec))
                if (e.path().extension() == ".exr" || e.path().extension() == ".hdr") maps_.push_back(e.path().filename().string());
        std::sort(maps_.begin(), maps_.end());
        GLFWwindow* w = window_.glfw();
        glfwSetWindowUserPointer(w, &input_);
        glfwSetScrollCallback(w, [](GLFWwindow* win, double, double dy) {
            static_cast<Input*>(glfwGetWindowUserPointer(win))->scroll += dy;
        });
        glfwSetKeyCallback(w, [](GLFWwindow* win, int key, int, int action, int) {
            if (action == GLFW_PRESS || action == GLFW_REPEAT) static_cast<Input*>(glfwGetWindowUserPointer(win))->keys.push_back(key);
        });
        settings_.timed = true;  // the panel's and the title's breakdown
        gui_ = std::make_unique<Gui>(w);
    }
    ~Viewer() { gui_.reset(); }  // the panel before the scene's GL objects and the window

    ViewerResult run() {
        if (!o_.script.empty()) {
            ImGui::GetIO().ConfigFlags |= ImGuiConfigFlags_NoMouse;  // a script's pictures: no hover from the pointer
            for (const ViewerAction& a : o_.script) {
                if (closed()) break;
                if (a.kind == ViewerAction::Kind::frames) {
                    for (int i = 0; i < static_cast<int>(a.x) && !closed(); ++i) frame();
                    continue;
                }
                apply(a);
                frame();  // each change shows in the next frame
            }
            if (o_.offscreen_frames > 0) {
                int fb_w, fb_h;
                glfwGetFramebufferSize(window_.glfw(), &fb_w, &fb_h);
                const Camera cam = camera_at(fb_w, fb_h);
                const RenderTarget target = camera_target(cam, 1);
                target.bind();
                result_.offscreen = time_shell_frames(*scene_.renderer, cam, settings_, false, o_.offscreen_frames);
            }
            return result_;
        }
        while (!closed() && (o_.frames == 0 || result_.frames < o_.frames)) {
            // Refined and nothing running: wait for the person (a tenth of a second at most, for the panel).
            if (showing_refined_ && !fit_) glfwWaitEventsTimeout(0.1);
            else glfwPollEvents();
            if (!handle_input()) break;
            frame();
        }
        return result_;
    }

private:
    static HairSceneDesc scene_desc(ViewerOptions& o, CookCache* cache) {
        HairSceneDesc d = std::move(o.scene);
        d.headless = false;
        d.absorption = o.absorption ? &*o.absorption : nullptr;  // the options outlive the viewer (run_viewer)
        d.cook_cache = cache;
        return d;
    }

    bool closed() const { return glfwWindowShouldClose(window_.glfw()); }

    // One script action (no drawing).
    void apply(const ViewerAction& a) {
        using K = ViewerAction::Kind;
        try {
            switch (a.kind) {
                case K::orbit:
                    camera_.azimuth = glm::radians(a.x);
                    camera_.elevation = glm::radians(a.y);
                    break;
                case K::zoom: camera_.zoom = std::clamp(camera_.zoom * a.x, kMinZoom, kMaxZoom); break;
                case K::pan: camera_.pan += glm::dvec2(a.x, a.y); break;
                case K::fit: fit(); break;
                case K::set: settings_ = shell_settings_from_json(a.values, a.where, settings_); break;
                case K::params: settings_ = read_shell_settings(a.path.string(), settings_); break;
                case K::background: environment_ = a.on; break;
                case K::exposure: exposure_ = static_cast<float>(a.x); break;
                case K::screenshot: screenshot(a.path); break;
                case K::capture: capture(a.path); break;
                case K::panel: show_panel_ = a.on; break;
                case K::symmetry: authoring_.set_symmetry(a.on); break;
                case K::paint: {
                    int fb_w, fb_h;
                    glfwGetFramebufferSize(window_.glfw(), &fb_w, &fb_h);
                    if (a.x < 0 || a.y < 0 || a.x >= fb_w || a.y >= fb_h)
                        throw Error::parameter("paint", "the point lies outside the " + std::to_string(fb_w) + "x" +
                                                            std::to_string(fb_h) + " window");
                    authoring_.begin_stroke();
                    dab(a.x, a.y, Brush{a.radius, a.strength, a.sigma_a});
                    break;
                }
                case K::undo: undo(); break;
                case K::redo: redo(); break;
                case K::save_absorption: save_absorption(a.path); break;
                case K::rotate_lights:
                    rotation_deg_ = a.x;
                    set_lights();
                    break;
                case K::env:  // a script waits for the fit
                    unrotated_ = environment_lights(a.path, fit_settings(a.lights));
                    environment_label_ = a.path.string();
                    set_lights();
                    break;
                case K::frames: break;
                case K::select: authoring_.select(a.names); break;
                case K::pick: {
                    int fb_w, fb_h;
                    glfwGetFramebufferSize(window_.glfw(), &fb_w, &fb_h);
                    authoring_.pick(camera_at(fb_w, fb_h), scene_.renderer->prepared(), a.x, a.y);
                    break;
                }
                case K::add: {
                    int fb_w, fb_h;
                    glfwGetFramebufferSize(window_.glfw(), &fb_w, &fb_h);
                    authoring_.add(camera_at(fb_w, fb_h), orientation(), a.x, a.y);
                    sync();
                    break;
                }
                case K::drag_point: {
                    int fb_w, fb_h;
                    glfwGetFramebufferSize(window_.glfw(), &fb_w, &fb_h);
                    // As the mouse drags (handle_input): the drag starts at `from`, the cursor passes the steps.
                    drag_point_ = a.point;
                    drag_from_ = drag_applied_ = {a.x, a.y};
                    end_live();
                    for (int k = 1; k <= a.steps; ++k)
                        drag_to(glm::mix(drag_from_, glm::dvec2(a.to_x, a.to_y), double(k) / a.steps), fb_w, fb_h, a.axis);
                    drag_point_ = -1;
                    end_live();
                    break;
                }
                case K::transform: {
                    const std::vector<std::size_t> sel = selected();
                    authoring_.edit_clusters(sel, [&](HairStyle& st) {
                        transform_clusters(st, sel, similarity_about(st, sel, a.translate, a.rotate_deg, a.scale));
                    });
                    sync();
                    break;
                }
                case K::duplicate:
                    authoring_.duplicate(selected(), !a.as_copy, a.translate);
                    sync();
                    break;
                case K::mirror:
                    authoring_.edit([&](HairStyle& st, AbsorptionMap* map) {
                        return mirror_clusters(st, selected(), a.axis, a.at ? *a.at : roots_middle(st, a.axis), map);
                    });
                    sync();
                    break;
                case K::remove:
                    authoring_.remove(selected());
                    sync();
                    break;
                case K::profile: {
                    const std::vector<std::size_t> sel = selected();
                    if (sel.size() != 1) throw Error::parameter("profile", "select one cluster to set its profile");
                    authoring_.edit_cluster(sel[0], [&](HairStyle& st) { set_profile(st, sel[0], a.profile, a.profile_values); });
                    sync();
                    break;
                }
                case K::layers: {
                    const std::vector<std::size_t> sel = selected();
                    if (sel.size() != 1) throw Error::parameter("layers", "select one cluster to set its layer count");
                    authoring_.edit_cluster(sel[0], [&](HairStyle& st) { set_layers(st, sel[0], a.point); });
                    sync();
                    break;
                }
                case K::save_style: save_style(a.path); break;
            }
        } catch (const Error& e) {
            throw Error(e.file(), e.place(), e.problem() + " (" + a.where + ")");
        }
    }

    void fit() {
        camera_.zoom = 1.0;
        camera_.pan = glm::dvec2(0.0);
    }

    // Mouse and keys since the last frame; false: quit.
    bool handle_input() {
        GLFWwindow* w = window_.glfw();
        const ImGuiIO& io = ImGui::GetIO();
        if (show_panel_ && io.WantCaptureKeyboard) input_.keys.clear();  // typing into the panel
        if (show_panel_ && io.WantCaptureMouse) {                          // using the panel
            input_.scroll = 0;
            dragging_ = false;
            return true;
        }
        for (const int key : input_.keys) {
            switch (key) {
                case GLFW_KEY_ESCAPE:  // an armed "add" is disarmed first
                    if (adding_) {
                        adding_ = false;
                        break;
                    }
                    return false;
                case GLFW_KEY_Q: return false;
                case GLFW_KEY_F: fit(); break;
                case GLFW_KEY_B: environment_ = !environment_; break;
                case GLFW_KEY_TAB: show_panel_ = !show_panel_; break;
                case GLFW_KEY_EQUAL:
                case GLFW_KEY_KP_ADD: exposure_ += kExposureStep; break;
                case GLFW_KEY_MINUS:
                case GLFW_KEY_KP_SUBTRACT: exposure_ -= kExposureStep; break;
                case GLFW_KEY_S: screenshot_key(); break;
                case GLFW_KEY_Z:
                    if (control(w)) shift(w) ? redo() : undo();
                    break;
                case GLFW_KEY_Y:
                    if (control(w)) redo();
                    else axis_lock_ = axis_lock_ == 1 ? -1 : 1;
                    break;
                case GLFW_KEY_X: axis_lock_ = axis_lock_ == 0 ? -1 : 0; break;
                case GLFW_KEY_DELETE: cluster_edit("delete"); break;
                default: break;
            }
        }
        input_.keys.clear();
        if (input_.scroll != 0) {
            camera_.zoom = std::clamp(camera_.zoom * std::pow(kZoomPerStep, input_.scroll), kMinZoom, kMaxZoom);
            input_.scroll = 0;
        }
        double x, y;
        glfwGetCursorPos(w, &x, &y);
        const bool left = glfwGetMouseButton(w, GLFW_MOUSE_BUTTON_LEFT) == GLFW_PRESS;
        const bool right = glfwGetMouseButton(w, GLFW_MOUSE_BUTTON_RIGHT) == GLFW_PRESS;
        int win_w, win_h, fb_w, fb_h;
        glfwGetWindowSize(w, &win_w, &win_h);
        glfwGetFramebufferSize(w, &fb_w, &fb_h);
        const glm::dvec2 at(x * fb_w / std::max(win_w, 1), y * fb_h / std::max(win_h, 1));  // framebuffer pixels
        // Cluster authoring: Alt + click selects the cluster under the cursor; a left drag from one of its control
        // points' handles moves that point with the cursor, once a frame, one undo step for the whole drag.
        if (drag_point_ >= 0) {
            try {
                if (at != drag_applied_) drag_to(at, fb_w, fb_h, axis_lock_);
                message_.clear();
            } catch (const Error& e) {
                message_ = e.what();
            }
            if (!left) {
                drag_point_ = -1;
                end_live();
            }
            last_x_ = x, last_y_ = y;
            return true;
        }
        // "add" armed in the panel: the next click plants a cluster there (one undo step).
        if (left && adding_) {
            adding_ = false;
            try {
                authoring_.add(camera_at(fb_w, fb_h), orientation(), at.x, at.y);
                sync();
                message_.clear();
            } catch (const Error& e) {
                message_ = e.what();
            }
            picking_ = true;  // the press is spent: no orbit until it is let go
            return true;
        }
        if (picking_ && left) return true;
        if (left && alt(w)) {
            if (!picking_) authoring_.pick(camera_at(fb_w, fb_h), scene_.renderer->prepared(), at.x, at.y, shift(w));
            picking_ = true;
            return true;
        }
        picking_ = false;
        if (left && !dragging_ && !control(w) && !shift(w)) {
            const std::vector<glm::vec2> h = handles(fb_w, fb_h);
            for (std::size_t i = 0; i < h.size(); ++i)
                if (glm::distance(glm::dvec2(h[i]), at) <= kHandleRadius + 2) {
                    drag_point_ = static_cast<int>(i);
                    drag_from_ = drag_applied_ = at;
                    end_live();
                    return true;
                }
        }
        // Ctrl + left drag paints (one stroke, one undo step), at the cursor, each frame.
        if (left && control(w)) {
            if (!stroking_) authoring_.begin_stroke();
            stroking_ = true;
            dab(at.x, at.y, brush_);
            dragging_ = false;
            last_x_ = x;
            last_y_ = y;
            return true;
        }
        stroking_ = false;
        const bool panning = right || (left && shift(w)), orbiting = left && !shift(w);
        if (dragging_ && (panning || orbiting)) {
            const double dx = x - last_x_, dy = y - last_y_;
            if (orbiting) {
                camera_.azimuth -= kDragRadiansPerPixel * dx;
                camera_.elevation = std::clamp(camera_.elevation + kDragRadiansPerPixel * dy, -kMaxElevation, kMaxElevation);
            } else {
                camera_.pan += camera_.zoom * glm::dvec2(-dx, dy) / double(std::max(fb_h, 1));
            }
        }
        dragging_ = panning || orbiting;
        last_x_ = x;
        last_y_ = y;
        return true;
    }

    // The lights drawn: the environment's, turned by rotation_deg_; the shadows follow (rerun on the next frame).
    void set_lights() {
        scene_.lights = rotate_srbf_lights_y(unrotated_, srbf_rotation_radians(rotation_deg_));
        scene_.renderer->set_lights(scene_.lights);
        lights_ = make_lights_buffer(scene_.lights);
        ++version_;
    }

    // A finished fit swaps its lights in; a failed one says why.
    void poll_fit() {
        if (!fit_ || fit_->lights.wait_for(std::chrono::seconds(0)) != std::future_status::ready) return;
        try {
            unrotated_ = fit_->lights.get();
            environment_label_ = fit_->label;
            set_lights();
            message_ = "fitted " + fit_->label;
        } catch (const Error& e) {
            message_ = e.what();
        }
        fit_.reset();
    }

    void start_fit(const std::filesystem::path& map, int count) {
        fit_.emplace();
        fit_->label = map.filename().string() + " (" + std::to_string(count) + " SRBF lights)";
        std::atomic<int>* iteration = &fit_->iteration;
        fit_->lights = std::async(std::launch::async, [map, count, iteration] {
            return environment_lights(map, fit_settings(count), [iteration](int i, int) { *iteration = i; });
        });
    }

    // The panel's environment: the lights' turn, and a map of maps_folder fitted with a chosen count.
    void environment_panel() {
        if (!ImGui::CollapsingHeader("environment", ImGuiTreeNodeFlags_DefaultOpen)) return;
        ImGui::TextWrapped("%s", environment_label_.c_str());
        float turn = static_cast<float>(rotation_deg_);
        if (ImGui::SliderFloat("turn (deg)", &turn, -180.0f, 180.0f, "%.0f")) {
            rotation_deg_ = turn;
            set_lights();
        }
        if (maps_.empty()) return;
        std::vector<const char*> names;
        for (const auto& m : maps_) names.push_back(m.c_str());
        ImGui::Combo("map", &map_choice_, names.data(), static_cast<int>(names.size()));
        ImGui::SliderInt("SRBF lights", &fit_count_, 1, 200);
        if (fit_) {
            const double seconds = std::chrono::duration<double>(Clock::now() - fit_->start).count();
            const int iteration = fit_->iteration.load();
            const float done = static_cast<float>(iteration) / float(SrbfFitSettings{}.max_iterations);
            char text[64];
            std::snprintf(text, sizeof text, "fitting: iteration %d, %.0f s", iteration, seconds);
            ImGui::ProgressBar(std::min(done, 1.0f), ImVec2(-1, 0), text);
        } else if (ImGui::Button("fit and light with it")) {
            start_fit(o_.maps_folder / maps_[static_cast<std::size_t>(map_choice_)], fit_count_);
        }
    }

    // The hair's colour as melanin concentrations (Chiang et al. 2016; shaders/hair_parameters.h): sets sigma_a.
    void colour_panel() {
        if (!ImGui::CollapsingHeader("hair colour (melanin)")) return;
        bool changed = ImGui::SliderFloat("eumelanin", &eumelanin_, 0.0f, 8.0f, "%.2f");
        changed |= ImGui::SliderFloat("pheomelanin", &pheomelanin_, 0.0f, 3.0f, "%.2f");
        if (ImGui::IsItemHovered()) ImGui::SetTooltip("blond ≈ 0.3, brown ≈ 1.3, black ≈ 8 eumelanin; red hair adds pheomelanin");
        if (changed) settings_.hair.fibre.sigma_a = shading::sigma_a_from_melanin(eumelanin_, pheomelanin_);
    }

    static bool control(GLFWwindow* w) {
        return glfwGetKey(w, GLFW_KEY_LEFT_CONTROL) == GLFW_PRESS || glfwGetKey(w, GLFW_KEY_RIGHT_CONTROL) == GLFW_PRESS;
    }
    static bool alt(GLFWwindow* w) {
        return glfwGetKey(w, GLFW_KEY_LEFT_ALT) == GLFW_PRESS || glfwGetKey(w, GLFW_KEY_RIGHT_ALT) == GLFW_PRESS;
    }
    static bool shift(GLFWwindow* w) {
        return glfwGetKey(w, GLFW_KEY_LEFT_SHIFT) == GLFW_PRESS || glfwGetKey(w, GLFW_KEY_RIGHT_SHIFT) == GLFW_PRESS;
    }

    // Painting (online/shells/painting.h): the renderer draws the painted map, or σa from the parameters.
    void apply_paint() {
        scene_.renderer->set_absorption(authoring_.map());
        ++version_;
    }
    void undo() {
        if (authoring_.undo()) sync();
    }
    void redo() {
        if (authoring_.redo()) sync();
    }
    void save_absorption(const std::filesystem::path& path) {
        if (!authoring_.map()) throw Error::parameter("absorption", "nothing is painted yet, so there is no map to save");
        write_absorption_map(path, *authoring_.map());
        result_.written.push_back(path);
    }
    // Cluster authoring (online/shells/authoring.h): the selection, the style's turn into the shells' space, the shells
    // cooked again after an edit (only when the style changed: undoing a stroke does not), and saving the style.
    std::vector<std::size_t> selected() const {
        if (authoring_.selection().empty()) throw Error::parameter("edit", "no cluster is selected (Alt + click, or a script's select)");
        return authoring_.selection();
    }
    glm::mat3 orientation() const { return authoring_.style() ? style_orientation(*authoring_.style()) : glm::mat3(1.0f); }
    void sync() {
        if (authoring_.style() && authoring_.style_version() != cooked_version_) {
            const auto t0 = Clock::now();
            const HairStyle& st = *authoring_.style();
            try {
                CookedShells cooked = scene_.cook(st, lighting_rows_, &cook_cache_);
                int fb_w = 0, fb_h = 0;
                glfwGetFramebufferSize(window_.glfw(), &fb_w, &fb_h);
                refuse_eye_inside(camera_at(fb_w, fb_h), cooked.shells.bounds_min, cooked.shells.bounds_max);
                // The same renderer, its programs compiled; the camera keeps its framing: an edit does not move the view.
                scene_.renderer->set_hair(std::move(cooked));
            } catch (const Error&) {  // e.g. the eye inside the edited hair: back to the style drawn, and say why
                authoring_.undo();
                cooked_version_ = authoring_.style_version();
                apply_paint();
                throw;
            }
            scene_.style = st;
            cooked_version_ = authoring_.style_version();
            recook_ms_ = std::chrono::duration<double, std::milli>(Clock::now() - t0).count();
            const CookCache::Timings& ct = cook_cache_.timings();
            log_message(LogLevel::info, "coif view: applied the edit in " + std::to_string(static_cast<int>(recook_ms_)) +
                                            " ms (cooked in " + std::to_string(static_cast<int>(ct.total_ms)) + " ms: " +
                                            std::to_string(ct.prototypes_made) + " of " + std::to_string(ct.prototypes) +
                                            " prototypes and " + std::to_string(ct.clusters_sampled) + " of " +
                                            std::to_string(ct.clusters) + " clusters' strands made anew, the shadow grid " +
                                            (ct.grid_rebuilt ? "voxelized again" : "updated") + ")");
        }
        apply_paint();
    }
    // An edit that follows the cursor or a field while it is dragged (a live gesture): the gesture's last edit undone
    // (without a cook) and `apply` made and cooked (what it did not change kept: CookCache), so that the gesture is one
    // undo step; end_live() ends it. A refused edit or a failed cook ends it, with the style as it was before it drawn,
    // and is rethrown.
    void live_edit(const std::function<void()>& apply) {
        try {
            if (live_) authoring_.undo();
            live_ = false;
            apply();
            live_ = true;
            sync();
        } catch (const Error&) {
            live_ = false;
            cooked_version_ = ~std::uint64_t{0};  // the renderer may hold the gesture's last cook: cook what is now
            sync();
            throw;
        }
    }
    void end_live() { live_ = false; }
    // The dragged control point moved with the cursor, from where the drag started (live_edit).
    void drag_to(glm::dvec2 at, int fb_w, int fb_h, int axis) {
        try {
            live_edit([&] { authoring_.drag_point(camera_at(fb_w, fb_h), orientation(), drag_point_, drag_from_, at, axis); });
            drag_applied_ = at;
        } catch (const Error&) {
            drag_point_ = -1;
            throw;
        }
    }
    void save_style(const std::filesystem::path& path) {
        if (!authoring_.style()) throw Error::parameter("style", "a baked asset is view-only: there is no style to save");
        write_style(path, *authoring_.style());
        result_.written.push_back(path);
    }

    // The selected cluster's trajectory control points, in framebuffer pixels (top-left origin): the drag handles, one
    // per control point in its order (NaN for a point behind the eye).
    std::vector<glm::vec2> handles(int width, int height) const {
        std::vector<glm::vec2> out;
        if (!authoring_.style() || authoring_.selection().size() != 1) return out;
        const Cluster& c = authoring_.style()->clusters[authoring_.selection()[0]];
        const Camera cam = camera_at(width, height);
        const glm::mat4 vp = cam.projection() * cam.view();
        const glm::mat3 turn = orientation();
        for (const glm::dvec3& p : authoring_.style()->clusters[c.prototype].shape->trajectory().control()) {
            const glm::vec4 clip = vp * glm::vec4(turn * glm::vec3(c.placement.apply(p)), 1.0f);
            if (clip.w <= 0.0f) {  // behind the eye: no handle (NaN keeps the points' indices)
                out.emplace_back(NAN, NAN);
                continue;
            }
            out.emplace_back((0.5f + 0.5f * clip.x / clip.w) * float(width), (0.5f - 0.5f * clip.y / clip.w) * float(height));
        }
        return out;
    }

    // The panel's and the keys' edits of the selection; a refusal is shown, not thrown.
    void cluster_edit(const std::string& what) {
        try {
            const std::vector<std::size_t> sel = selected();
            if (what == "delete") authoring_.remove(sel);
            else if (what == "mirror")
                authoring_.edit([&](HairStyle& st, AbsorptionMap* map) { return mirror_clusters(st, sel, 0, roots_middle(st, 0), map); });
            else {  // a copy beside the original: moved by its cluster's mean half-axis along x
                const Cluster& c = authoring_.style()->clusters[sel[0]];
                authoring_.duplicate(sel, true, {2.0 * c.placement.scale * c.shape->a(0.5), 0.0, 0.0});
            }
            sync();
            message_.clear();
        } catch (const Error& e) {
            message_ = e.what();
        }
    }

    // The selected cluster's A, B and θ control points (its prototype's: every instance of it changes too): a field
    // dragged or typed in changes the style as it changes (live_edit), one undo step until it is let go.
    void profile_widgets() {
        const std::size_t c = authoring_.selection()[0];
        // Copies: a row's edit replaces the style (a live edit drops the one it replaces), so no reference into it is kept.
        const std::shared_ptr<const GeneralizedCylinder> g = authoring_.style()->clusters[authoring_.style()->clusters[c].prototype].shape;
        const auto row = [&](const char* name, const Spline1& spline, double unit, float lo, float hi) {
            std::vector<float> v;
            for (const double x : spline.control()) v.push_back(static_cast<float>(x * unit));
            bool edited = false, let_go = false;
            ImGui::PushID(name);
            for (std::size_t i = 0; i < v.size(); ++i) {
                ImGui::PushID(static_cast<int>(i));
                ImGui::DragFloat(i == 0 ? name : "##more", &v[i], 0.01f * (hi - lo), lo, hi, "%.3g");
                edited |= ImGui::IsItemEdited();
                let_go |= ImGui::IsItemDeactivated();
                ImGui::PopID();
            }
            ImGui::PopID();
            if (edited) {
                const std::vector<double> values(v.begin(), v.end());
                try {
                    live_edit([&] { authoring_.edit_cluster(c, [&](HairStyle& s2) { set_profile(s2, c, name, values); }); });
                    message_.clear();
                } catch (const Error& e) {
                    message_ = e.what();
                }
            }
            if (let_go) end_live();
        };
        if (!ImGui::TreeNode("profiles (root to tip)")) return;
        const float size = static_cast<float>(2.0 * std::max(g->a(0.5), g->b(0.5)) + 1.0);
        row("a", g->a_spline(), 1.0, 1e-3f, 4.0f * size);
        row("b", g->b_spline(), 1.0, 1e-3f, 4.0f * size);
        row("theta_deg", g->theta_spline(), kDegreesPerRadian, -360.0f, 360.0f);
        // Its own number of layered shells (its prototype's), an edit when the field is let go.
        int layers = authoring_.style()->layout_of(c).layers;
        ImGui::InputInt("layers", &layers, 1, 1);
        if (ImGui::IsItemDeactivatedAfterEdit() || (ImGui::IsItemEdited() && !ImGui::IsItemActive())) {
            try {
                authoring_.edit_cluster(c, [&](HairStyle& s2) { set_layers(s2, c, std::clamp(layers, 1, kMaxLayers)); });
                sync();
                message_.clear();
            } catch (const Error& e) {
                message_ = e.what();
            }
        }
        ImGui::TreePop();
    }

    // The panel's cluster section, and the handles drawn over the picture.
    // The camera, a control point or a profile field is dragged: frames are drawn at half size and the low preset
    // (kDragDivisor).
    bool moving() const { return dragging_ || drag_point_ >= 0 || live_; }
    void clusters_panel(int width, int height) {
        const ImVec2 scale = ImGui::GetIO().DisplayFramebufferScale;
        ImDrawList* overlay = ImGui::GetForegroundDrawList();
        const std::vector<glm::vec2> hs = handles(width * (moving() ? kDragDivisor : 1), height * (moving() ? kDragDivisor : 1));
        for (const glm::vec2 h : hs)
            if (!std::isnan(h.x)) overlay->AddCircleFilled(ImVec2(h.x / scale.x, h.y / scale.y), kHandleRadius, IM_COL32(255, 200, 40, 220));
        if (drag_point_ >= 0 && static_cast<std::size_t>(drag_point_) < hs.size() && !std::isnan(hs[static_cast<std::size_t>(drag_point_)].x)) {
            // where the dragged point goes (the handle is where the last frame's edit put it)
            const glm::vec2 h = hs[static_cast<std::size_t>(drag_point_)];
            const ImVec2 from(h.x / scale.x, h.y / scale.y), mouse = ImGui::GetMousePos();
            const ImVec2 to(from.x + mouse.x - float(drag_applied_.x) / scale.x, from.y + mouse.y - float(drag_applied_.y) / scale.y);
            overlay->AddLine(from, to, IM_COL32(255, 200, 40, 255), 2.0f);
            overlay->AddCircle(to, kHandleRadius + 2, IM_COL32(255, 255, 255, 255), 0, 2.0f);
        }
        // A new selection opens the section, so that what can be done with it shows.
        if (authoring_.selection() != shown_selection_ && !authoring_.selection().empty()) ImGui::SetNextItemOpen(true);
        shown_selection_ = authoring_.selection();
        if (!ImGui::CollapsingHeader("clusters (Alt + click selects)")) return;
        ImGui::TextWrapped("Alt + Shift + click adds or removes a cluster");
        if (!authoring_.style()) {
            ImGui::TextWrapped("a baked asset is view-only: open its style to edit clusters");
            return;
        }
        std::string names;
        for (const std::size_t c : authoring_.selection()) names += (names.empty() ? "" : ", ") + authoring_.style()->clusters[c].name;
        ImGui::TextWrapped("selected: %s", names.empty() ? "none" : names.c_str());
        ImGui::TextWrapped("drag a handle to move a control point; X / Y lock the drag to an axis (%s)",
                           axis_lock_ < 0 ? "free" : axis_lock_ == 0 ? "x" : "y");
        bool symmetry = authoring_.symmetry();
        if (ImGui::Checkbox("symmetry (x)", &symmetry)) authoring_.set_symmetry(symmetry);
        if (authoring_.selection().size() == 1) {
            const std::optional<std::size_t> partner = authoring_.symmetric_partner(authoring_.selection()[0]);
            if (authoring_.symmetry())
                ImGui::TextWrapped("mirror partner: %s",
                                   partner ? authoring_.style()->clusters[*partner].name.c_str() : "none (edits stay on this side)");
            profile_widgets();
        }
        if (ImGui::Button(adding_ ? "click where it grows (Esc: no)" : "add")) adding_ = !adding_;
        if (ImGui::IsItemHovered())
            ImGui::SetTooltip("a new cluster rooted on the scalp where you click next, shaped like its nearest neighbour");
        ImGui::SameLine();
        if (ImGui::Button("duplicate")) cluster_edit("duplicate");
        ImGui::SameLine();
        if (ImGui::Button("mirror (x)")) cluster_edit("mirror");
        ImGui::SameLine();
        if (ImGui::Button("delete (Del)")) cluster_edit("delete");
        if (ImGui::Button("undo (Ctrl+Z)##clusters")) undo();
        ImGui::SameLine();
        if (ImGui::Button("redo (Ctrl+Y)##clusters")) redo();
        save_row("style file", style_path_, sizeof style_path_, "save style", "coif render --style",
                 [&](const std::filesystem::path& p) { save_style(p); });
        if (recook_ms_ > 0) ImGui::Text("last edit cooked in %.0f ms", recook_ms_);
    }

    // One dab at window pixel (x, y), top-left origin.
    void dab(double x, double y, const Brush& brush) {
        int fb_w, fb_h;
        glfwGetFramebufferSize(window_.glfw(), &fb_w, &fb_h);
        if (authoring_.painting().dab(camera_at(fb_w, fb_h), scene_.renderer->prepared(), x, y, brush, settings_.hair.fibre.sigma_a))
            apply_paint();
    }

    // A file name field and its save button; the outcome, or why it failed, shown in the panel.
    void save_row(const char* field, char* path, std::size_t size, const char* button, const char* reader,
                  const std::function<void(const std::filesystem::path&)>& save) {
        ImGui::InputText(field, path, size);
        if (!ImGui::Button(button)) return;
        try {
            save(path);
            message_ = std::string("saved ") + path + " (" + reader + ")";
        } catch (const Error& e) {
            message_ = e.what();
        }
    }

    // The panel's brush.
    void paint_panel() {
        if (!ImGui::CollapsingHeader("paint absorption (Ctrl + drag)")) return;
        float radius = static_cast<float>(brush_.radius), strength = static_cast<float>(brush_.strength);
        if (ImGui::SliderFloat("radius (px)", &radius, 1.0f, 100.0f, "%.0f")) brush_.radius = radius;
        if (ImGui::SliderFloat("strength", &strength, 0.0f, 1.0f, "%.2f")) brush_.strength = strength;
        ImGui::DragFloat3("brush sigma_a", &brush_.sigma_a.x, 0.01f, 0.0f, 50.0f, "%.3g");
        if (ImGui::Button("brush = melanin colour")) brush_.sigma_a = shading::sigma_a_from_melanin(eumelanin_, pheomelanin_);
        if (ImGui::Button("undo (Ctrl+Z)")) undo();
        ImGui::SameLine();
        if (ImGui::Button("redo (Ctrl+Y)")) redo();
        ImGui::SameLine();
        if (ImGui::Button("clear") && authoring_.map()) {
            authoring_.clear_paint();
            apply_paint();
        }
        save_row("map file", absorption_path_, sizeof absorption_path_, "save map", "coif render --absorption",
                 [&](const std::filesystem::path& p) { save_absorption(p); });
        if (authoring_.map()) ImGui::TextWrapped("painted: the map's σa replaces sigma_a below");
    }

    // The S key and the panel's button: a screenshot that, failing, says why and lets the viewer go on.
    void screenshot_key() {
        const std::filesystem::path p = o_.screenshot.empty()
                                            ? std::filesystem::path("coif-view-" + std::to_string(++shots_) + ".png")
                                            : o_.screenshot;
        try {
            screenshot(p);
            message_ = "wrote " + p.string();
            log_message(LogLevel::info, message_);
        } catch (const Error& e) {
            message_ = e.what();
            log_message(LogLevel::warning, message_);
        }
    }

    // The panel (Dear ImGui): the frame's figures, the view, and every parameter of `coif render --params`, made
    // from its table (online/shells/shell_settings.h) with its units, ranges and help.
    void panel(int width, int height) {
        // At the window's right edge, over the environment rather than the hair (framed in the middle).
        const ImVec2 display = ImGui::GetIO().DisplaySize;
        ImGui::SetNextWindowPos(ImVec2(display.x - 8, 8), ImGuiCond_FirstUseEver, ImVec2(1, 0));
        ImGui::SetNextWindowSize(ImVec2(kPanelWidth, display.y - 16), ImGuiCond_FirstUseEver);
        ImGui::SetNextWindowBgAlpha(0.8f);
        ImGui::Begin("coif view (Tab hides)");
        ImGui::PushItemWidth(-kPanelLabels);
        const ShellTimings& t = scene_.renderer->timings();
        if (result_.frames == 0) ImGui::Text("%dx%d  the first frame", width, height);
        else  // the frame before this one, display included
            ImGui::Text("%dx%d  %.0f ms (%.1f fps)%s", width, height, result_.last_frame_ms,
                        1000.0 / std::max(result_.last_frame_ms, 1e-3), moving() ? "  half size, quality low" : "");
        ImGui::Text("lighting %.0f ms, shells %.0f ms (resolve %.0f)", t.lighting_wall_ms, t.shells_wall_ms, t.resolve_wall_ms);
        ImGui::SliderFloat("exposure (stops)", &exposure_, -10.0f, 10.0f, "%.2f");
        ImGui::Checkbox("environment (B)", &environment_);
        ImGui::SameLine();
        if (ImGui::Button("frame (F)")) fit();
        ImGui::SameLine();
        if (ImGui::Button("shot (S)")) screenshot_key();
        environment_panel();
        colour_panel();
        paint_panel();
        clusters_panel(width, height);
        if (ImGui::CollapsingHeader("parameters (--params)", ImGuiTreeNodeFlags_DefaultOpen)) {
            ShellSettings edited = settings_;
            bool changed = false;
            for (const Param<ShellSettings>& p : shell_settings_table()) changed |= param_widget(p, edited);
            if (changed) {
                try {
                    shading::validate(edited.hair, "the hair parameters");  // together a valid hair (e.g. β_TRT = 2 β_R)
                    settings_ = edited;
                    message_.clear();
                } catch (const Error& e) {
                    message_ = e.what();
                }
            }
            ImGui::InputText("file", params_path_, sizeof params_path_);
            if (ImGui::Button("save")) {
                try {
                    write_shell_settings(params_path_, settings_);
                    message_ = std::string("saved ") + params_path_;
                } catch (const Error& e) {
                    message_ = e.what();
                }
            }
            ImGui::SameLine();
            if (ImGui::Button("load")) {
                try {
                    settings_ = read_shell_settings(params_path_, settings_);
                    message_ = std::string("loaded ") + params_path_;
                } catch (const Error& e) {
                    message_ = e.what();
                }
            }
            ImGui::SameLine();
            if (ImGui::Button("start values")) settings_ = start_settings();
        }
        if (!message_.empty()) ImGui::TextWrapped("%s", message_.c_str());
        ImGui::PopItemWidth();
        ImGui::End();
    }

    ShellSettings start_settings() const {
        ShellSettings s = o_.settings;
        s.timed = true;
        return s;
    }

    Camera camera_at(int width, int height) const {
        return camera_.camera(o_.view, scene_.frame_min, scene_.frame_max, width, height);
    }

    // What a frame's picture depends on, but for the exposure (the display pass applies it): when it has not
    // changed since the last frame, the picture is refined instead of drawn again.
    struct FrameKey {
        int width = 0, height = 0;
        double azimuth = 0, elevation = 0, zoom = 0;
        glm::dvec2 pan{0.0};
        bool environment = false;
        std::string settings;        // the parameters as their file writes them
        std::uint64_t version = 0;   // lights and painting
        bool operator==(const FrameKey&) const = default;
    };

    // Draws one frame: the hair over the background into a linear target (half size and the low quality preset while the camera is dragged),
    // then the display pass into the window. While nothing changes, the next kRefineGrid² frames draw the picture
    // again shifted within the pixel (the sub-pixel offsets of coif render's supersampling) and their average
    // replaces it (refined when still); after that, frames only display. ViewerOptions::offscreen_frames (the
    // benchmark) draws every frame.
    void frame() {
        const auto start = Clock::now();
        poll_fit();
        GLFWwindow* w = window_.glfw();
        int fb_w, fb_h;
        glfwGetFramebufferSize(w, &fb_w, &fb_h);
        if (fb_w <= 0 || fb_h <= 0) return;  // minimised
        const int divisor = moving() ? kDragDivisor : 1;
        const int width = std::max(1, fb_w / divisor), height = std::max(1, fb_h / divisor);
        if (target_width_ != width || target_height_ != height) make_target(width, height);
        const FrameKey key{width, height, camera_.azimuth, camera_.elevation, camera_.zoom, camera_.pan, environment_,
                           shell_settings_json(settings_).dump(), version_};
        const bool still = key == last_key_ && !moving() && o_.offscreen_frames == 0;
        last_key_ = key;
        // Levels of detail keep their hysteresis only through a drag; any other frame picks them as coif render does.
        if (!moving()) scene_.renderer->forget_detail();
        if (!still) {
            draw_picture(glm::vec2(0.0f), width, height, framebuffer_);
            refined_ = 0;
            showing_refined_ = false;
        } else if (refined_ < kRefineGrid * kRefineGrid) {
            const int i = refined_ % kRefineGrid, j = refined_ / kRefineGrid;
            const glm::vec2 jitter((i + 0.5f) / kRefineGrid - 0.5f, (j + 0.5f) / kRefineGrid - 0.5f);
            draw_picture(jitter, width, height, sub_framebuffer_);  // the picture shown stays until the average is done
            accumulate(width, height, refined_ == 0);
            if (++refined_ == kRefineGrid * kRefineGrid) showing_refined_ = true;
        }
        present(fb_w, fb_h);
        if (show_panel_) draw_panel(width, height);
        glfwSwapBuffers(w);
        glFinish();  // the frame's time includes the GPU's work
        check_errors("viewer frame");
        ++result_.frames;
        result_.last_frame_ms = std::chrono::duration<double, std::milli>(Clock::now() - start).count();
        result_.frame_ms.push_back(result_.last_frame_ms);
        const ShellTimings& t = scene_.renderer->timings();
        char title[256];
        std::snprintf(title, sizeof title, "coif view  %dx%d  %.0f ms (lighting %.0f, shells %.0f)  %s%s%s", width, height,
                      result_.last_frame_ms, t.lighting_wall_ms, t.shells_wall_ms, environment_ ? "environment" : "background",
                      divisor > 1 ? "  [half size, quality low, while dragging]" : "", showing_refined_ ? "  [refined]" : "");
        glfwSetWindowTitle(w, title);
    }

    // The hair over the background, seen `jitter` pixels shifted (x right, y down), into `fbo`.
    void draw_picture(glm::vec2 jitter, int width, int height, const Framebuffer& fbo) {
        const Camera cam = camera_at(width, height);
        // The shift as coif render's supersampling applies it (online/shell_passes.cpp): in the projection.
        const glm::mat4 projection = pixel_shift(jitter, width, height) * cam.projection();
        ShellRenderer& r = *scene_.renderer;
        glBindFramebuffer(GL_FRAMEBUFFER, fbo.id());
        glViewport(0, 0, width, height);
        // While the camera or a control point is dragged, the low preset (ShellSettings' quality presets) on top of the
        // panel's parameters.
        ShellSettings s = settings_;
        if (moving()) apply_quality(s, Quality::low);
        // A frame whose fragments overflowed the exact compositing's storage has holes; the storage has grown
        // since, so it is drawn again (the first frame, a closer view).
        for (int attempt = 0; attempt < 2; ++attempt) {
            FrameTarget t;
            t.viewport = glm::ivec4(0, 0, width, height);
            if (environment_) {
                draw_environment(cam, projection, width, height);
                t.over = true;
            }
            if (r.has_body()) {  // coif view --body: the body over the background, the hair over both, hidden behind it
                if (!environment_) {
                    const float bg[4] = {s.background.x, s.background.y, s.background.z, 1.0f};
                    glClearBufferfv(GL_COLOR, 0, bg);
                }
                t.scene_depth = r.draw_body(FrameView::of(cam.view(), projection), width, height, scene_.lights);
                t.depth_test = DepthTest::less_equal;
                t.over = true;
            }
            r.draw_frame(cam.view(), projection, scene_.lights, s, t, {});
            if (s.compositing != Compositing::exact || r.fragment_list_stats().dropped == 0) break;
        }
    }

    // Adds the shifted frame just drawn into the refinement's sum (RGBA32F; cleared first on the first one).
    void accumulate(int width, int height, bool first) {
        glBindFramebuffer(GL_FRAMEBUFFER, sum_framebuffer_.id());
        glViewport(0, 0, width, height);
        if (first) {
            const float zero[4] = {0, 0, 0, 0};
            glClearBufferfv(GL_COLOR, 0, zero);
        }
        glDisable(GL_DEPTH_TEST);
        glEnable(GL_BLEND);
        glBlendEquation(GL_FUNC_ADD);
        glBlendFunc(GL_ONE, GL_ONE);
        copy_.use();
        glBindTextureUnit(0, sub_.id());
        glUniform1i(copy_.uniform("u_image"), 0);
        glUniform2i(copy_.uniform("u_origin"), 0, 0);
        glBindVertexArray(empty_vao_.id());
        glDrawArrays(GL_TRIANGLES, 0, 3);
        glDisable(GL_BLEND);
    }

    // The display pass: the linear frame → exposure, clip, sRGB, into the window's back buffer.
    void present(int fb_w, int fb_h) {
        glBindFramebuffer(GL_FRAMEBUFFER, 0);
        glViewport(0, 0, fb_w, fb_h);
        glDisable(GL_BLEND);
        glDisable(GL_DEPTH_TEST);
        present_.use();
        glBindTextureUnit(0, showing_refined_ ? sum_.id() : color_.id());
        glUniform1i(present_.uniform("u_image"), 0);
        glUniform2f(present_.uniform("u_size"), float(fb_w), float(fb_h));
        // The refined sum's average: its kRefineGrid² frames, a power of two, so the scale is exact.
        const float average = showing_refined_ ? 1.0f / float(kRefineGrid * kRefineGrid) : 1.0f;
        glUniform1f(present_.uniform("u_exposure_scale"), std::exp2(exposure_) * average);
        glBindVertexArray(empty_vao_.id());
        glDrawArrays(GL_TRIANGLES, 0, 3);
    }

    void draw_panel(int width, int height) {
        gui_->new_frame();
        panel(width, height);
        gui_->render();
    }

    // The frame shown (RGBA16F, with depth), the refinement's shifted frame (the same) and their sum (RGBA32F).
    void make_target(int width, int height) {
        GLuint id = 0;
        glCreateRenderbuffers(1, &id);
        depth_ = Renderbuffer(id);
        glNamedRenderbufferStorage(id, GL_DEPTH_COMPONENT32F, width, height);
        const auto framebuffer = [&](const Texture& color, bool depth) {
            GLuint fbo = 0;
            glCreateFramebuffers(1, &fbo);
            Framebuffer f(fbo);
            glNamedFramebufferTexture(fbo, GL_COLOR_ATTACHMENT0, color.id(), 0);
            if (depth) glNamedFramebufferRenderbuffer(fbo, GL_DEPTH_ATTACHMENT, GL_RENDERBUFFER, depth_.id());
            if (glCheckNamedFramebufferStatus(fbo, GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE)
                throw Error::parameter("viewer", "its framebuffer is incomplete");
            return f;
        };
        const Sampling linear{GL_LINEAR, GL_CLAMP_TO_EDGE};
        color_ = make_texture_2d(GL_RGBA16F, width, height, linear);
        framebuffer_ = framebuffer(color_, true);
        sub_ = make_texture_2d(GL_RGBA16F, width, height);
        sub_framebuffer_ = framebuffer(sub_, true);
        sum_ = make_texture_2d(GL_RGBA32F, width, height, linear);
        sum_framebuffer_ = framebuffer(sum_, false);
        target_width_ = width;
        target_height_ = height;
    }

    // The environment's SRBF lights along every pixel's ray (shaders/gl/viewer_background.frag).
    void draw_environment(const Camera& cam, const glm::mat4& projection, int width, int height) {
        glDisable(GL_BLEND);
        glDisable(GL_DEPTH_TEST);
        glClear(GL_DEPTH_BUFFER_BIT);
        background_.use();
        glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 3, lights_.id());
        glUniform1i(background_.uniform("u_light_count"), static_cast<int>(scene_.lights.size()));
        const glm::mat4 inverse = glm::inverse(projection * cam.view());
        glUniformMatrix4fv(background_.uniform("u_inverse_view_projection"), 1, GL_FALSE, &inverse[0][0]);
        glUniform3fv(background_.uniform("u_eye"), 1, &cam.eye[0]);
        glUniform4f(background_.uniform("u_viewport"), 0.0f, 0.0f, float(width), float(height));
        glBindVertexArray(empty_vao_.id());
        glDrawArrays(GL_TRIANGLES, 0, 3);
    }

    // What `coif render` writes for this camera at the window's size and these parameters (same renderer, same
    // render(): the same pixels).
    void screenshot(const std::filesystem::path& path) {
        int fb_w, fb_h;
        glfwGetFramebufferSize(window_.glfw(), &fb_w, &fb_h);
        ShellSettings s = settings_;
        s.timed = false;
        const Image image = scene_.renderer->render(camera_at(fb_w, fb_h), s);
        WriteOptions wo;
        wo.exposure = exposure_;
        wo.description = "coif view: SATF shells, SRBF Marschner lighting; lights " + scene_.lights_label;
        write_image(path, image, wo);
        result_.written.push_back(path);
    }

    // The window's pixels as shown, sRGB bytes: decoded to linear so that the PNG writer's tone map (exposure 0)
    // encodes them back to the same bytes.
    void capture(const std::filesystem::path& path) {
        int fb_w, fb_h;
        glfwGetFramebufferSize(window_.glfw(), &fb_w, &fb_h);
        if (target_width_ == 0) frame();  // nothing drawn yet
        std::vector<std::uint8_t> rgba(static_cast<std::size_t>(fb_w) * fb_h * 4);
        present(fb_w, fb_h);  // the last frame shown, again into the back buffer, read before any swap
        if (show_panel_) gui_->render_again();
        glBindFramebuffer(GL_READ_FRAMEBUFFER, 0);
        glReadBuffer(GL_BACK);
        glPixelStorei(GL_PACK_ALIGNMENT, 1);
        glReadPixels(0, 0, fb_w, fb_h, GL_RGBA, GL_UNSIGNED_BYTE, rgba.data());
        Image img(fb_w, fb_h, 4);
        for (int y = 0; y < fb_h; ++y)
            for (int x = 0; x < fb_w; ++x)
                for (int c = 0; c < 4; ++c) {
                    const float v = rgba[(static_cast<std::size_t>(fb_h - 1 - y) * fb_w + x) * 4 + c] / 255.0f;
                    img.at(x, y)[c] = c == 3 ? 1.0f : srgb_to_linear(v);
                }
        WriteOptions wo;
        wo.description = "coif view: the window as shown";
        write_image(path, img, wo);
        result_.written.push_back(path);
    }

    ViewerOptions& o_;
    ShellSettings settings_;
    float exposure_;
    bool environment_;
    Window window_;  // before everything GL: its context is current while the rest is made and destroyed
    std::unique_ptr<Gui> gui_;  // after the viewer's GLFW callbacks, which its backend chains to
    bool show_panel_ = true;
    std::string message_;        // the last refusal or failure, shown in the panel
    char params_path_[512] = "params.json";
    double rotation_deg_ = 0;
    std::vector<SrbfLight> unrotated_;  // the environment's lights before the turn
    std::string environment_label_;
    std::vector<std::string> maps_;     // the maps in maps_folder
    int map_choice_ = 0, fit_count_ = 40;
    std::optional<LightsJob> fit_;
    float eumelanin_ = 1.3f, pheomelanin_ = 0.0f;
    Authoring authoring_;           // the style edited, the selection, the painting, and their one undo history
    int lighting_rows_ = 0;
    std::uint64_t cooked_version_ = 0;  // authoring_.style_version() of the style the renderer draws
    CookCache cook_cache_;          // what the last cook made, for the next (an edit makes only what it changed)
    double recook_ms_ = 0;          // the last edit's cooking
    int drag_point_ = -1;           // the control point the mouse drags (−1: none), from (drag_from_)
    glm::dvec2 drag_from_{0.0};
    glm::dvec2 drag_applied_{0.0};  // the cursor as the drag's edit last applied it (drag_from_ before any)
    bool live_ = false;             // a live gesture's edit is applied (the top undo step): live_edit
    int axis_lock_ = -1;            // X, Y, Z keys: drags along that axis only
    char style_path_[512] = "style.json";
    Brush brush_;
    bool stroking_ = false;  // Ctrl + left button held: one stroke
    bool picking_ = false;   // Alt + left button held: one pick (or the click that added a cluster)
    bool adding_ = false;    // the panel's "add": the next click plants a cluster
    std::vector<std::size_t> shown_selection_;  // the selection the panel last drew
    char absorption_path_[512] = "absorption.exr";
    HairScene scene_;
    Program background_, present_, copy_;  // the environment, the display pass, the refinement's adds
    Buffer lights_;  // scene_.lights for the environment pass (set_lights)
    VertexArray empty_vao_;
    Texture color_, sub_, sum_;  // the frame shown; the refinement's shifted frame, and their sum
    Renderbuffer depth_;
    Framebuffer framebuffer_, sub_framebuffer_, sum_framebuffer_;
    FrameKey last_key_;
    std::uint64_t version_ = 0;  // bumped by every change of the lights or the painting
    int refined_ = 0;            // shifted frames summed since the picture last changed
    bool showing_refined_ = false;
    int target_width_ = 0, target_height_ = 0;  // of the targets made (0: none yet)
    ViewerCamera camera_;
    Input input_;
    bool dragging_ = false;
    double last_x_ = 0, last_y_ = 0;
    int shots_ = 0;
    ViewerResult result_;
};

}  // namespace

ViewerResult run_viewer(ViewerOptions options) {
    Viewer viewer(options);
    return viewer.run();
}

}  // namespace coif::gl
