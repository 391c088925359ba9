#pragma once
// The viewer's panel (Dear ImGui): its context in the window, and a parameter table (models/core/param_table.h)
// entry as a widget, so that every key of a parameters file is edited with its unit, range and help.
#include <algorithm>
#include <cmath>
#include <imgui.h>
#include <string>
#include <vector>

#include "models/core/param_table.h"

struct GLFWwindow;

namespace coif::gl {

// Dear ImGui in the window: its context and backends, made after the viewer's own GLFW callbacks (which the
// backend chains to) and torn down before the window. The parameters' help speaks Greek (σa, η, β_R): DejaVu Sans
// (Debian's fonts-dejavu-core) with the Greek and punctuation ranges; ImGui's built-in ASCII font if it is missing.
class Gui {
public:
    explicit Gui(GLFWwindow* window);  // throws coif::Error when the backends cannot start
    ~Gui();
    Gui(const Gui&) = delete;
    Gui& operator=(const Gui&) = delete;

    void new_frame();  // before the panel's widgets
    void render();     // after them: draws the panel into the bound framebuffer
    void render_again();  // the last frame's panel again (a capture of the window as shown)
};

// One parameter of a table (models/core/param_table.h) as a widget, in its interface unit; true when changed.
template <class T>
bool param_widget(const Param<T>& p, T& target) {
    bool changed = false;
    const std::string& label = p.key;  // the unit and range are in the tooltip
    const double lo = p.min, hi = std::isfinite(p.max) ? p.max : p.min + 1e3 * std::max(1.0, std::abs(p.min) + 1.0);
    switch (p.kind) {
        case ParamKind::real:
        case ParamKind::rgb: {
            double v[3];
            for (int c = 0; c < p.components(); ++c) v[c] = p.get(target, c);
            const bool wide = hi - lo > 1000.0;  // σa's 0 … 10⁴: dragged, not slid
            changed = wide ? ImGui::DragScalarN(label.c_str(), ImGuiDataType_Double, v, p.components(), 0.01f, &lo, &hi, "%.4g")
                           : ImGui::SliderScalarN(label.c_str(), ImGuiDataType_Double, v, p.components(), &lo, &hi, "%.4g");
            if (changed)
                for (int c = 0; c < p.components(); ++c) {
                    double x = std::clamp(v[c], lo, hi);
                    if (p.min_exclusive && x <= p.min) x = std::nextafter(p.min, hi);
                    p.set(target, c, x);
                }
            break;
        }
        case ParamKind::integer: {
            int v = static_cast<int>(p.get(target, 0));
            const int ilo = static_cast<int>(lo), ihi = static_cast<int>(std::min(hi, 1e6));
            if ((changed = ImGui::SliderInt(label.c_str(), &v, ilo, ihi))) p.set(target, 0, std::clamp(v, ilo, ihi));
            break;
        }
        case ParamKind::boolean: {
            bool v = p.get(target, 0) != 0.0;
            if ((changed = ImGui::Checkbox(label.c_str(), &v))) p.set(target, 0, v ? 1.0 : 0.0);
            break;
        }
        case ParamKind::choice: {
            int v = static_cast<int>(p.get(target, 0));
            std::vector<const char*> names;
            for (const std::string& n : p.names) names.push_back(n.c_str());
            if ((changed = ImGui::Combo(label.c_str(), &v, names.data(), static_cast<int>(names.size())))) p.set(target, 0, v);
            break;
        }
        case ParamKind::flags: {
            unsigned bits = static_cast<unsigned>(p.get(target, 0));
            ImGui::TextUnformatted(label.c_str());
            for (std::size_t i = 0; i < p.names.size(); ++i) {
                bool on = bits & (1u << i);
                ImGui::SameLine();
                if (ImGui::Checkbox((p.names[i] + "##" + p.key).c_str(), &on)) {
                    bits = on ? bits | (1u << i) : bits & ~(1u << i);
                    changed = true;
                }
            }
            if (changed) p.set(target, 0, bits);
            break;
        }
    }
    if (ImGui::IsItemHovered() && !p.help.empty()) ImGui::SetTooltip("%s\n%s", p.help.c_str(), accepted_text(p).c_str());
    return changed;
}


}  // namespace coif::gl
