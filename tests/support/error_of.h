#pragma once
// The message of the workbench::Error a call throws, or "no error": tests compare whole messages.
#include <workbench/error.h>

#include <functional>
#include <string>

namespace test_support {

inline std::string error_of(const std::function<void()>& f) {
  try {
    f();
  } catch (const workbench::Error& e) {
    return e.what();
  }
  return "no error";
}

}  // namespace test_support
