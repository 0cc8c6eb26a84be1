#pragma once
// A count and its noun for human-readable messages: "1 trial", "2 trials".
#include <string>
#include <string_view>

namespace pronk::run {

/// "1 trial", "0 trials", "5 trials": `n`, a space, and `singular` (n == 1) or `plural`
/// (empty: `singular` + "s").
std::string count_text(long n, std::string_view singular, std::string_view plural = {});

}  // namespace pronk::run
