// Internal invariants, checked always (release builds too: Drake's DEMAND tier). A failed
// check is a bug in lubcore, not bad input: it throws lub::InternalError (a
// std::logic_error), which no input error (lub::InputError, std::invalid_argument) is, so
// callers and tests can tell the two apart. Use it where a wrong size or index would
// otherwise read or write out of bounds: at the boundary between a model and the workspace
// or integrator state it is handed.
#pragma once

#include <stdexcept>
#include <string>

namespace lub {

/// A broken internal invariant (a bug), never a user's mistake.
class InternalError : public std::logic_error {
 public:
  using std::logic_error::logic_error;
};

namespace detail {
[[noreturn]] inline void assertion_failed(const char* condition, const char* file, int line, const std::string& what) {
  throw InternalError(std::string("internal error: ") + condition + " failed at " + file + ":" +
                      std::to_string(line) + (what.empty() ? "" : ": " + what));
}
}  // namespace detail

}  // namespace lub

/// Always-on check of an internal invariant: throws lub::InternalError naming the condition,
/// the place and `what` (a std::string or string literal) if `condition` is false.
#define LUB_ASSERT(condition, what)                                                      \
  do {                                                                                   \
    if (!(condition)) ::lub::detail::assertion_failed(#condition, __FILE__, __LINE__, what); \
  } while (false)
