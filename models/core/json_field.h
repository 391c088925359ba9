#pragma once
// Reading one typed field of a JSON object, with an error that names its JSON path
// ("<where>/<key>: missing" or the type error). The file is added by the caller's handler.
#include <nlohmann/json.hpp>
#include <string>

#include "models/core/error.h"

namespace coif {

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
