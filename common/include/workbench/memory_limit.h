#pragma once
// The one memory limit of the workbench: a problem whose estimated memory exceeds it is refused
// before anything large is allocated (docs/reliability.md, "Input validation").
#include <string>

namespace workbench {

constexpr double kGiB = 1024.0 * 1024.0 * 1024.0;

/// The limit in bytes: WORKBENCH_MEMORY_LIMIT (GiB, e.g. "64") when set, else the machine's
/// physical memory. An unreadable WORKBENCH_MEMORY_LIMIT is an Error.
double memory_limit_bytes();

/// Throws Error "<what>: <size>, an estimated <bytes> GiB, above the memory limit of <limit> GiB
/// (...WORKBENCH_MEMORY_LIMIT...)" when `estimated_bytes` exceeds the limit.
void check_memory_estimate(const std::string& what, const std::string& size, double estimated_bytes);

}  // namespace workbench
