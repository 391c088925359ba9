#pragma once
// Parsing a file's JSON text, and reading one typed field of a JSON object with an error that names its
// JSON path ("<where>/<key>: missing" or the type error; the file is added by the caller's handler).
#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>
#include <string_view>

#include "models/core/error.h"

namespace coif {

// The JSON document in `text`, read from `file`. Every way nlohmann refuses text becomes a coif::Error naming
// the file: a syntax error (at its byte), and also a number that overflows a double ("1e999"), which nlohmann
// reports as out_of_range rather than parse_error (the fuzzer found a lights file that escaped that way).
template <class Json = nlohmann::json>
Json parse_json(std::string_view text, const std::filesystem::path& file) {
    try {
        return Json::parse(text.begin(), text.end());
    } catch (const nlohmann::json::parse_error& e) {
        throw Error(file, "byte " + std::to_string(e.byte), std::string("not valid JSON: ") + e.what());
    } catch (const nlohmann::json::exception& e) {
        throw Error(file, "", std::string("not valid JSON: ") + e.what());
    }
}

template <class T>
T json_field(const nlohmann::json& j, const char* key, const char* where) {
    if (!j.contains(key)) throw Error({}, std::string(where) + "/" + key, "missing");
    try {
        return j.at(key).get<T>();
    } catch (const nlohmann::json::exception& e) {
        throw Error({}, std::string(where) + "/" + key, e.what());
    }
}

}  // namespace coif
