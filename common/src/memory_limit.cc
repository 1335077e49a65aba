// The memory limit problems are checked against before they are built (one place for it).
#include <workbench/memory_limit.h>

#include <workbench/error.h>

#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>

namespace workbench {

namespace {

std::string gib(double bytes) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.3g GiB", bytes / kGiB);
  return buf;
}
}  // namespace

double memory_limit_bytes() {
  if (const char* env = std::getenv("WORKBENCH_MEMORY_LIMIT"); env && *env) {
    char* end = nullptr;
    const double v = std::strtod(env, &end);
    if (end == env || *end != '\0' || !std::isfinite(v) || !(v > 0))
      throw Error(std::string("WORKBENCH_MEMORY_LIMIT: must be a number of GiB > 0 (got \"") + env + "\")");
    return v * kGiB;
  }
  const long pages = sysconf(_SC_PHYS_PAGES), page = sysconf(_SC_PAGE_SIZE);
  return pages > 0 && page > 0 ? double(pages) * double(page) : 16 * kGiB;
}

void check_memory_estimate(const std::string& what, const std::string& size, double estimated_bytes) {
  const double limit = memory_limit_bytes();
  if (!(estimated_bytes <= limit))
    throw Error(what + ": " + size + " need an estimated " + gib(estimated_bytes) + ", above the memory limit of " +
                gib(limit) + " (set WORKBENCH_MEMORY_LIMIT=<GiB> to raise it)");
}

}  // namespace workbench
