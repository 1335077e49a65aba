// agent::ExactFunctions: a flag per thread, set for the scope of each object.
#include <agent/exact_functions.h>

namespace agent {

namespace {
thread_local bool exact_functions = false;
}  // namespace

ExactFunctions::ExactFunctions() : outer_(exact_functions) { exact_functions = true; }
ExactFunctions::~ExactFunctions() { exact_functions = outer_; }
bool ExactFunctions::active() { return exact_functions; }

}  // namespace agent
