#include "models/core/log.h"

#include <cstdio>
#include <mutex>
#include <utility>

namespace coif {
namespace {

std::mutex& sink_mutex() {
    static std::mutex m;
    return m;
}
LogSink& current_sink() {
    static LogSink sink;
    return sink;
}

}  // namespace

LogSink set_log_sink(LogSink sink) {
    const std::lock_guard<std::mutex> lock(sink_mutex());
    return std::exchange(current_sink(), std::move(sink));
}

void log_message(LogLevel level, std::string_view message) {
    const std::lock_guard<std::mutex> lock(sink_mutex());
    if (current_sink()) {
        current_sink()(level, message);
        return;
    }
    std::fprintf(stderr, "coif: %s%.*s\n", level == LogLevel::warning ? "warning: " : "", static_cast<int>(message.size()),
                 message.data());
}

}  // namespace coif
