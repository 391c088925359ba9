// models/core/json_field.h: every way nlohmann refuses text is a coif::Error naming the file. A number that
// overflows a double is nlohmann's out_of_range, not its parse_error; one escaped the lights reader as an
// uncaught exception until the fuzzer found it.
#include <gtest/gtest.h>

#include <string>

#include "models/core/error.h"
#include "models/core/json_field.h"

namespace {

std::string refusal(const std::string& text) {
    try {
        coif::parse_json(text, "p.json");
    } catch (const coif::Error& e) {
        return e.what();
    }
    return "accepted";
}

TEST(ParseJson, RefusalsNameTheFile) {
    EXPECT_NE(refusal("{\"a\": 1e999}").find("p.json"), std::string::npos);
    EXPECT_NE(refusal("{\"a\": 1e999}").find("not valid JSON"), std::string::npos);
    EXPECT_NE(refusal("{\"a\": ").find("p.json"), std::string::npos);
    EXPECT_NE(refusal("{\"a\": ").find("byte"), std::string::npos);
    EXPECT_EQ(coif::parse_json<nlohmann::ordered_json>("{\"b\": 2, \"a\": 1}", "p.json").begin().key(), "b");
}

}  // namespace
