#include "online/window/viewer_script.h"

#include <cmath>
#include <fstream>
#include <sstream>

#include "models/absorption_map.h"
#include "models/core/error.h"
#include "models/core/image.h"
#include "models/generalized_disk.h"
#include "offline/srbf_lights.h"
#include "online/shells/shell_settings.h"

namespace coif::gl {
namespace {

double number(const nlohmann::json& v, const std::string& file, const std::string& place, double lo, double hi) {
    if (!v.is_number()) throw Error(file, place, "expected a number");
    const double x = v.get<double>();
    if (!std::isfinite(x) || x < lo || x > hi)
        throw Error(file, place, "must be " + std::to_string(lo) + " … " + std::to_string(hi) + ", not " + v.dump());
    return x;
}

std::filesystem::path image_path(const nlohmann::json& v, const std::string& file, const std::string& place, bool exr) {
    if (!v.is_string() || v.get<std::string>().empty()) throw Error(file, place, "expected a file name");
    std::filesystem::path p = v.get<std::string>();
    const std::string ext = image_extension(p);
    if (ext != ".png" && !(exr && ext == ".exr"))
        throw Error(file, place, std::string("the image must be a .png") + (exr ? " or .exr" : "") + ", not '" + p.string() + "'");
    return p;
}

}  // namespace

std::vector<ViewerAction> read_viewer_script(const std::filesystem::path& path) {
    const std::string file = path.string();
    std::ifstream in(path);
    if (!in) throw Error(file, "", "cannot open the script");
    std::stringstream text;
    text << in.rdbuf();
    nlohmann::json doc;
    try {
        doc = nlohmann::json::parse(text.str());
    } catch (const nlohmann::json::parse_error& e) {
        throw Error(file, "byte " + std::to_string(e.byte), "not JSON");
    }
    if (!doc.is_array()) throw Error(file, "", "expected a JSON array of actions (coif view --help)");
    if (doc.size() > 100000) throw Error(file, "", "more than 100000 actions");
    std::vector<ViewerAction> actions;
    for (std::size_t i = 0; i < doc.size(); ++i) {
        const std::string place = "action " + std::to_string(i + 1);
        const nlohmann::json& a = doc[i];
        if (!a.is_object() || a.size() != 1) throw Error(file, place, "expected an object with one key, e.g. {\"orbit\": [90, 10]}");
        const std::string key = a.begin().key();
        const nlohmann::json& v = a.begin().value();
        const std::string at = place + " (" + key + ")";
        ViewerAction act;
        act.where = file + ": " + place;
        using K = ViewerAction::Kind;
        if (key == "orbit" || key == "pan") {
            if (!v.is_array() || v.size() != 2) throw Error(file, at, "expected two numbers");
            act.kind = key == "orbit" ? K::orbit : K::pan;
            const double lim = key == "orbit" ? 3600.0 : 100.0;
            act.x = number(v[0], file, at, -lim, lim);
            act.y = number(v[1], file, at, key == "orbit" ? -89.0 : -lim, key == "orbit" ? 89.0 : lim);
        } else if (key == "zoom") {
            act.kind = K::zoom;
            act.x = number(v, file, at, 0.1, 10.0);
        } else if (key == "fit") {
            act.kind = K::fit;
            if (v != true) throw Error(file, at, "expected true");
        } else if (key == "set") {
            act.kind = K::set;
            if (!v.is_object() || v.empty()) throw Error(file, at, "expected an object of parameters");
            (void)shell_settings_from_json(v, file + ": " + at);  // refused here, before anything is drawn
            act.values = v;
        } else if (key == "params") {
            act.kind = K::params;
            if (!v.is_string()) throw Error(file, at, "expected a parameters file name");
            act.path = v.get<std::string>();
            try {
                (void)read_shell_settings(act.path.string());
            } catch (const Error& e) {
                throw Error(file, at, e.what());
            }
        } else if (key == "background" || key == "panel" || key == "symmetry") {
            act.kind = key == "background" ? K::background : key == "panel" ? K::panel : K::symmetry;
            if (!v.is_boolean()) throw Error(file, at, "expected true or false");
            act.on = v.get<bool>();
        } else if (key == "exposure") {
            act.kind = K::exposure;
            act.x = number(v, file, at, -20.0, 20.0);
        } else if (key == "rotate_lights") {
            act.kind = K::rotate_lights;
            act.x = number(v, file, at, -3600.0, 3600.0);
        } else if (key == "env") {
            act.kind = K::env;
            const nlohmann::json* f = &v;
            if (v.is_object()) {
                if (!v.contains("file") || v.size() > 2 || (v.size() == 2 && !v.contains("lights")))
                    throw Error(file, at, "expected {\"file\": NAME, \"lights\": N}");
                f = &v["file"];
                if (v.contains("lights")) act.lights = static_cast<int>(number(v["lights"], file, at + "/lights", 1, kMaxSrbfLights));
            }
            if (!f->is_string() || f->get<std::string>().empty()) throw Error(file, at, "expected a lights JSON or a map file name");
            act.path = f->get<std::string>();
            if (!std::filesystem::is_regular_file(act.path)) throw Error(file, at, "no such file: " + act.path.string());
        } else if (key == "paint") {
            act.kind = K::paint;
            if (!v.is_object() || !v.contains("at")) throw Error(file, at, "expected {\"at\": [X, Y], …}");
            for (const auto& [k, x] : v.items()) {
                if (k == "at") {
                    if (!x.is_array() || x.size() != 2) throw Error(file, at + "/at", "expected two numbers");
                    act.x = number(x[0], file, at + "/at", 0, 16384);
                    act.y = number(x[1], file, at + "/at", 0, 16384);
                } else if (k == "radius") {
                    act.radius = number(x, file, at + "/radius", 0, 1000);
                } else if (k == "strength") {
                    act.strength = number(x, file, at + "/strength", 0, 1);
                } else if (k == "sigma_a") {
                    if (!x.is_array() || x.size() != 3) throw Error(file, at + "/sigma_a", "expected three numbers");
                    for (int c = 0; c < 3; ++c)
                        act.sigma_a[c] = static_cast<float>(number(x[c], file, at + "/sigma_a", 0, kMaxPaintedSigmaA));
                } else {
                    throw Error(file, at, "unknown key '" + k + "' (at, radius, strength, sigma_a)");
                }
            }
        } else if (key == "undo" || key == "redo") {
            act.kind = key == "undo" ? K::undo : K::redo;
            if (v != true) throw Error(file, at, "expected true");
        } else if (key == "save_absorption") {
            act.kind = K::save_absorption;
            if (!v.is_string() || v.get<std::string>().empty()) throw Error(file, at, "expected a file name");
            act.path = v.get<std::string>();
            if (act.path.extension() != ".exr") throw Error(file, at, "the map must be an .exr, not '" + act.path.string() + "'");
        } else if (key == "frames") {
            act.kind = K::frames;
            act.x = number(v, file, at, 1.0, 10000.0);
            if (act.x != std::floor(act.x)) throw Error(file, at, "expected a whole number");
        } else if (key == "screenshot") {
            act.kind = K::screenshot;
            act.path = image_path(v, file, at, true);
        } else if (key == "capture") {
            act.kind = K::capture;
            act.path = image_path(v, file, at, false);
        } else if (key == "select") {
            act.kind = K::select;
            if (!v.is_array()) throw Error(file, at, "expected an array of cluster names");
            for (const auto& n : v) {
                if (!n.is_string()) throw Error(file, at, "expected cluster names");
                act.names.push_back(n.get<std::string>());
            }
        } else if (key == "pick" || key == "add") {
            act.kind = key == "pick" ? K::pick : K::add;
            if (!v.is_array() || v.size() != 2) throw Error(file, at, "expected [X, Y]");
            act.x = number(v[0], file, at, 0, 16384);
            act.y = number(v[1], file, at, 0, 16384);
        } else if (key == "drag_point") {
            act.kind = K::drag_point;
            if (!v.is_object() || !v.contains("point") || !v.contains("from") || !v.contains("to"))
                throw Error(file, at, "expected {\"point\": I, \"from\": [X, Y], \"to\": [X, Y], \"axis\": …}");
            for (const auto& [k, x] : v.items()) {
                if (k == "point") {
                    act.point = static_cast<int>(number(x, file, at + "/point", 0, 4095));
                    if (x.get<double>() != act.point) throw Error(file, at + "/point", "expected a whole number");
                } else if (k == "from" || k == "to") {
                    if (!x.is_array() || x.size() != 2) throw Error(file, at + "/" + k, "expected [X, Y]");
                    (k == "from" ? act.x : act.to_x) = number(x[0], file, at + "/" + k, 0, 16384);
                    (k == "from" ? act.y : act.to_y) = number(x[1], file, at + "/" + k, 0, 16384);
                } else if (k == "axis") {
                    if (x == "view") act.axis = -1;
                    else if (x == "x" || x == "y" || x == "z") act.axis = x.get<std::string>()[0] - 'x';
                    else throw Error(file, at + "/axis", "expected view, x, y or z");
                } else if (k == "steps") {
                    act.steps = static_cast<int>(number(x, file, at + "/steps", 1, 1000));
                    if (x.get<double>() != act.steps) throw Error(file, at + "/steps", "expected a whole number");
                } else {
                    throw Error(file, at, "unknown key '" + k + "' (point, from, to, axis, steps)");
                }
            }
        } else if (key == "transform" || key == "duplicate") {
            act.kind = key == "transform" ? K::transform : K::duplicate;
            if (!v.is_object()) throw Error(file, at, "expected an object");
            const auto vec3 = [&](const nlohmann::json& x, const std::string& where, double lim) {
                if (!x.is_array() || x.size() != 3) throw Error(file, where, "expected three numbers");
                return glm::dvec3(number(x[0], file, where, -lim, lim), number(x[1], file, where, -lim, lim), number(x[2], file, where, -lim, lim));
            };
            for (const auto& [k, x] : v.items()) {
                if (k == "translate") act.translate = vec3(x, at + "/translate", 1e6);
                else if (k == "rotate_deg" && key == "transform") act.rotate_deg = vec3(x, at + "/rotate_deg", 3600);
                else if (k == "scale" && key == "transform") act.scale = number(x, file, at + "/scale", 1e-3, 1e3);
                else if (k == "as_copy" && key == "duplicate") {
                    if (!x.is_boolean()) throw Error(file, at + "/as_copy", "expected true or false");
                    act.as_copy = x.get<bool>();
                } else {
                    throw Error(file, at, "unknown key '" + k + "' (" + (key == "transform" ? "translate, rotate_deg, scale" : "translate, as_copy") + ")");
                }
            }
        } else if (key == "mirror") {
            act.kind = K::mirror;
            act.axis = 0;
            if (!v.is_object()) throw Error(file, at, "expected {\"axis\": \"x\", \"at\": X}");
            for (const auto& [k, x] : v.items()) {
                if (k == "axis") {
                    if (x != "x" && x != "y" && x != "z") throw Error(file, at + "/axis", "expected x, y or z");
                    act.axis = x.get<std::string>()[0] - 'x';
                } else if (k == "at") {
                    act.at = number(x, file, at + "/at", -1e6, 1e6);
                } else {
                    throw Error(file, at, "unknown key '" + k + "' (axis, at)");
                }
            }
        } else if (key == "delete") {
            act.kind = K::remove;
            if (v != true) throw Error(file, at, "expected true");
        } else if (key == "profile") {
            act.kind = K::profile;
            if (!v.is_object() || v.size() != 1 || !v.begin().value().is_array() || v.begin().value().empty())
                throw Error(file, at, "expected {\"a\" | \"b\" | \"theta_deg\": [V, …]}");
            act.profile = v.begin().key();
            if (act.profile != "a" && act.profile != "b" && act.profile != "theta_deg")
                throw Error(file, at, "unknown profile '" + act.profile + "' (a, b, theta_deg)");
            const bool radius = act.profile != "theta_deg";
            for (const auto& x : v.begin().value()) act.profile_values.push_back(number(x, file, at + "/" + act.profile, radius ? 1e-9 : -36000, radius ? 1e6 : 36000));
        } else if (key == "layers") {
            act.kind = K::layers;
            act.point = static_cast<int>(number(v, file, at, 1, kMaxLayers));
            if (v.get<double>() != act.point) throw Error(file, at, "expected a whole number");
        } else if (key == "save_style") {
            act.kind = K::save_style;
            if (!v.is_string() || v.get<std::string>().empty()) throw Error(file, at, "expected a file name");
            act.path = v.get<std::string>();
            if (act.path.extension() != ".json") throw Error(file, at, "the style must be a .json, not '" + act.path.string() + "'");
        } else {
            throw Error(file, place, "unknown action '" + key +
                                         "' (orbit, zoom, pan, fit, set, params, background, panel, exposure, rotate_lights, env, paint, undo, redo, "
                                         "save_absorption, frames, screenshot, capture, select, pick, drag_point, transform, duplicate, mirror, add, delete, "
                                         "profile, layers, save_style, symmetry)");
        }
        actions.push_back(std::move(act));
    }
    return actions;
}

}  // namespace coif::gl
