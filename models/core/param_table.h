#pragma once
// Parameter tables: the keys of a JSON parameters file written once, each with its unit, accepted range,
// help text and how to get and set it on a struct T. The file reader, the writer and the --help text are
// all made from a table, and a viewer can make its sliders from one (key, unit, range). One table per
// struct (shaders/hair_parameters.h for the hair, online/shells/shell_settings.h for the shell renderer);
// lift() puts one struct's table into an enclosing struct's.
//
// Values at the interface are doubles in the entry's unit: degrees for angles ("deg"; radians in the
// struct, DESIGN.md), RGB components one at a time, a choice as the index of its name, a set of flags as
// a bit set (bit i = names[i]), a boolean as 0 or 1. The struct's fields are floats: `set` rounds to
// float, and the writer writes each real as the shortest decimal that reads back as the same float, so
// that write → read gives the same struct (for an entry whose get inverts its set exactly; the hair's
// angles do wherever a float number of degrees reaches the radians, shaders/hair_parameters.h).
//
// The file: one JSON object, every key optional (absent keys keep the base struct's values). Reading
// refuses, as coif::Error(file, "JSON /<key>[/<part>]", what): a key in no table, a value of the wrong
// type, a real outside its range, a non-integer or out-of-range integer, an unknown choice or flag name.
// Keys are applied in table order, not file order, so a table may rely on an entry's side effects
// (the hair's α_R and β_R restore 000's links before the TT and TRT keys override them).
#include <algorithm>
#include <charconv>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <functional>
#include <glm/glm.hpp>
#include <limits>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <vector>

#include "models/core/error.h"
#include "models/core/json_field.h"

namespace coif {

enum class ParamKind { real, integer, boolean, rgb, choice, flags };

template <class T>
struct Param {
    std::string key;                  // JSON key, and a slider's label
    ParamKind kind = ParamKind::real;
    std::string unit;                 // interface unit ("deg": radians in the struct); "" for none
    double min = 0, max = 0;          // accepted range (real, integer, each rgb component); max may be +inf
    bool min_exclusive = false;       // (min, max] instead of [min, max]
    std::string help;
    std::vector<std::string> names;   // choice: the accepted strings; flags: the object's keys, bit i = names[i]
    std::function<double(const T&, int component)> get;  // the interface value (see the header comment)
    std::function<void(T&, int component, double)> set;
    std::function<bool(const T&)> written;  // empty: always written; else the writer leaves the key out when false

    int components() const { return kind == ParamKind::rgb ? 3 : 1; }
};

template <class T>
using ParamTable = std::vector<Param<T>>;

namespace param_detail {

inline std::string names_text(const std::vector<std::string>& names, const char* last_joiner) {
    std::string s;
    for (size_t i = 0; i < names.size(); ++i)
        s += (i == 0 ? "" : (i + 1 == names.size() ? last_joiner : ", ")) + names[i];
    return s;
}

// The shortest decimal that reads back as the same float (for the writer).
inline double shortest_float(double v) {
    char buf[64];
    const auto r = std::to_chars(buf, buf + sizeof buf, static_cast<float>(v));
    return std::strtod(std::string(buf, r.ptr).c_str(), nullptr);
}

}  // namespace param_detail

// "(1, 10]", "an integer 1..4", "true or false", "sorted, unsorted or exact", ...: what an entry accepts.
template <class T>
std::string accepted_text(const Param<T>& p) {
    const std::string unit = p.unit.empty() ? "" : " " + p.unit;
    switch (p.kind) {
        case ParamKind::real:
        case ParamKind::rgb:
            return std::string(p.min_exclusive ? "(" : "[") + number_text(p.min) + ", " + number_text(p.max) +
                   (std::isinf(p.max) ? ")" : "]") + unit;
        case ParamKind::integer: return "an integer " + number_text(p.min) + ".." + number_text(p.max);
        case ParamKind::boolean: return "true or false";
        case ParamKind::choice: return param_detail::names_text(p.names, " or ");
        case ParamKind::flags: return "an object of " + param_detail::names_text(p.names, " and ") + ", each true or false";
    }
    return "";
}

// Reads one entry's value (place: "JSON /key" in a file, "option --eta" on a command line).
template <class T>
void read_param(const Param<T>& p, const nlohmann::json& value, T& target, const std::filesystem::path& file,
                const std::string& place) {
    const auto real = [&](const nlohmann::json& v, const std::string& where) {
        if (!v.is_number()) throw Error(file, where, "expected a number");
        const double x = v.get<double>();
        const bool in_range = std::isfinite(x) && (p.min_exclusive ? x > p.min : x >= p.min) && x <= p.max;
        if (!in_range) throw Error(file, where, number_text(x) + " is outside " + accepted_text(p));
        return x;
    };
    switch (p.kind) {
        case ParamKind::real: p.set(target, 0, real(value, place)); return;
        case ParamKind::integer: {
            if (!value.is_number()) throw Error(file, place, "must be " + accepted_text(p));
            const double x = value.get<double>();
            if (!(x >= p.min && x <= p.max && x == std::floor(x))) throw Error(file, place, "must be " + accepted_text(p));
            p.set(target, 0, x);
            return;
        }
        case ParamKind::boolean:
            if (!value.is_boolean()) throw Error(file, place, "expected true or false");
            p.set(target, 0, value.get<bool>() ? 1.0 : 0.0);
            return;
        case ParamKind::rgb: {
            if (!value.is_array() || value.size() != 3) throw Error(file, place, "expected [r, g, b]");
            double c[3];
            for (int i = 0; i < 3; ++i) c[i] = real(value[static_cast<size_t>(i)], place + "/" + std::to_string(i));
            for (int i = 0; i < 3; ++i) p.set(target, i, c[i]);
            return;
        }
        case ParamKind::choice: {
            if (!value.is_string()) throw Error(file, place, "expected " + accepted_text(p) + " (a string)");
            const std::string s = value.get<std::string>();
            for (size_t i = 0; i < p.names.size(); ++i)
                if (s == p.names[i]) return p.set(target, 0, static_cast<double>(i));
            throw Error(file, place, "'" + s + "' is not " + accepted_text(p));
        }
        case ParamKind::flags: {
            if (!value.is_object()) throw Error(file, place, "expected " + accepted_text(p));
            int bits = static_cast<int>(p.get(target, 0));
            for (const auto& [name, on] : value.items()) {
                size_t i = 0;
                while (i < p.names.size() && p.names[i] != name) ++i;
                if (i == p.names.size() || !on.is_boolean())
                    throw Error(file, place + "/" + name, "expected " + param_detail::names_text(p.names, " or ") + " with true or false");
                bits = on.template get<bool>() ? (bits | (1 << i)) : (bits & ~(1 << i));
            }
            p.set(target, 0, bits);
            return;
        }
    }
}

// Reads a parameters object into `target` (see the header comment).
template <class T>
void read_params(const nlohmann::json& j, T& target, const ParamTable<T>& table, const std::filesystem::path& file) {
    if (!j.is_object()) throw Error(file, "JSON /", "expected an object of parameters");
    for (const auto& [key, value] : j.items()) {
        bool known = false;
        for (const Param<T>& p : table) known = known || p.key == key;
        if (!known) {
            std::string keys;
            for (const Param<T>& p : table) keys += (keys.empty() ? "" : ", ") + p.key;
            throw Error(file, "JSON /" + key, "unknown parameter (known: " + keys + ")");
        }
    }
    for (const Param<T>& p : table)
        if (j.contains(p.key)) read_param(p, j[p.key], target, file, "JSON /" + p.key);
}

// The JSON object of a file (not a parameters table's concern: opening and parsing, errors naming the byte).
inline nlohmann::json read_json_file(const std::filesystem::path& path, const char* what = "the parameters file") {
    std::ifstream in(path, std::ios::binary);
    if (!in) throw Error(path, "", std::string("cannot open ") + what);
    std::stringstream text;
    text << in.rdbuf();
    return parse_json(text.str(), path);
}

// Every written entry of `source`, in table order.
template <class T>
nlohmann::ordered_json write_params(const T& source, const ParamTable<T>& table) {
    nlohmann::ordered_json j = nlohmann::ordered_json::object();
    for (const Param<T>& p : table) {
        if (p.written && !p.written(source)) continue;
        switch (p.kind) {
            case ParamKind::real: j[p.key] = param_detail::shortest_float(p.get(source, 0)); break;
            case ParamKind::integer: j[p.key] = static_cast<long long>(p.get(source, 0)); break;
            case ParamKind::boolean: j[p.key] = p.get(source, 0) != 0.0; break;
            case ParamKind::rgb:
                j[p.key] = nlohmann::ordered_json::array();
                for (int i = 0; i < 3; ++i) j[p.key].push_back(param_detail::shortest_float(p.get(source, i)));
                break;
            case ParamKind::choice: j[p.key] = p.names.at(static_cast<size_t>(p.get(source, 0))); break;
            case ParamKind::flags: {
                const int bits = static_cast<int>(p.get(source, 0));
                j[p.key] = nlohmann::ordered_json::object();
                for (size_t i = 0; i < p.names.size(); ++i) j[p.key][p.names[i]] = (bits & (1 << i)) != 0;
                break;
            }
        }
    }
    return j;
}

// One line per key: "  key  accepted  help" (for --help texts).
template <class T>
std::string params_help(const ParamTable<T>& table) {
    size_t width = 0;
    for (const Param<T>& p : table) width = std::max(width, p.key.size());
    std::string s;
    for (const Param<T>& p : table)
        s += "  " + p.key + std::string(width + 2 - p.key.size(), ' ') + p.help + " (" + accepted_text(p) + ")\n";
    return s;
}

// `inner`'s entries as entries of Outer, reaching the Inner through `member`.
template <class Outer, class Inner>
ParamTable<Outer> lift(const ParamTable<Inner>& inner, Inner Outer::*member) {
    ParamTable<Outer> out;
    for (const Param<Inner>& p : inner) {
        Param<Outer> q;
        q.key = p.key;
        q.kind = p.kind;
        q.unit = p.unit;
        q.min = p.min;
        q.max = p.max;
        q.min_exclusive = p.min_exclusive;
        q.help = p.help;
        q.names = p.names;
        q.get = [get = p.get, member](const Outer& o, int c) { return get(o.*member, c); };
        q.set = [set = p.set, member](Outer& o, int c, double v) { set(o.*member, c, v); };
        if (p.written) q.written = [written = p.written, member](const Outer& o) { return written(o.*member); };
        out.push_back(std::move(q));
    }
    return out;
}

// ---- entries of the common kinds, on the field that `field` reaches: a generic lambda
// [](auto& t) -> auto& { return t.member; }, called on const T& by get and on T& by set ----

template <class T, class F>
Param<T> real_param(std::string key, std::string unit, double min, double max, std::string help, F field) {
    Param<T> p{std::move(key), ParamKind::real, std::move(unit), min, max, false, std::move(help), {}, {}, {}, {}};
    p.get = [field](const T& t, int) { return static_cast<double>(field(t)); };
    p.set = [field](T& t, int, double v) { field(t) = static_cast<float>(v); };
    return p;
}

template <class T, class F>
Param<T> rgb_param(std::string key, std::string unit, double min, double max, std::string help, F field) {
    Param<T> p{std::move(key), ParamKind::rgb, std::move(unit), min, max, false, std::move(help), {}, {}, {}, {}};
    p.get = [field](const T& t, int c) { return static_cast<double>(field(t)[c]); };
    p.set = [field](T& t, int c, double v) { field(t)[c] = static_cast<float>(v); };
    return p;
}

template <class T, class F>
Param<T> int_param(std::string key, int min, int max, std::string help, F field) {
    Param<T> p{std::move(key), ParamKind::integer, "", double(min), double(max), false, std::move(help), {}, {}, {}, {}};
    p.get = [field](const T& t, int) { return static_cast<double>(field(t)); };
    p.set = [field](T& t, int, double v) { field(t) = static_cast<int>(v); };
    return p;
}

template <class T, class F>
Param<T> bool_param(std::string key, std::string help, F field) {
    Param<T> p{std::move(key), ParamKind::boolean, "", 0, 1, false, std::move(help), {}, {}, {}, {}};
    p.get = [field](const T& t, int) { return field(t) ? 1.0 : 0.0; };
    p.set = [field](T& t, int, double v) { field(t) = v != 0.0; };
    return p;
}

// A bit set over `names` (bit i = names[i]), written as an object {"name": bool, ...}.
template <class T, class F>
Param<T> flags_param(std::string key, std::vector<std::string> names, std::string help, F field) {
    const double all = double((1 << names.size()) - 1);
    Param<T> p{std::move(key), ParamKind::flags, "", 0, all, false, std::move(help), std::move(names), {}, {}, {}};
    p.get = [field](const T& t, int) { return static_cast<double>(field(t)); };
    p.set = [field](T& t, int, double v) { field(t) = static_cast<int>(v); };
    return p;
}

}  // namespace coif
