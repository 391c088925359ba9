#pragma once
// The libraries' messages (a warning that a frame dropped fragments, a note that tables are being built): never
// straight to stderr, but through one sink that a host sets. The default sink writes "coif: <message>" to stderr,
// as the coif command wants. Thread-safe: the sink is called under a lock, from whichever thread logs.
#include <functional>
#include <string_view>

namespace coif {

enum class LogLevel { info, warning };
using LogSink = std::function<void(LogLevel, std::string_view message)>;

// Replaces the sink for every later message (null: the default, stderr). Returns the previous one.
LogSink set_log_sink(LogSink sink);
void log_message(LogLevel level, std::string_view message);

}  // namespace coif
