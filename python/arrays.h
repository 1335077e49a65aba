#pragma once
// numpy arrays from the C++ results' vectors, without copies (python/workbench_module.cc,
// python/bind_studies.cc, python/compared_fields.cc).
#include <agent/state.h>
#include <compare/compare_study.h>

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include <vector>

namespace workbench_python {

namespace py = pybind11;

/// A numpy array owning the vector's storage (moved, not copied).
template <class T>
py::array_t<T> take(std::vector<T>&& values, std::vector<py::ssize_t> shape) {
  auto* owner = new std::vector<T>(std::move(values));
  py::capsule free_owner(owner, [](void* p) { delete static_cast<std::vector<T>*>(p); });
  return py::array_t<T>(shape, owner->data(), free_owner);
}

inline py::ssize_t ssize(std::size_t n) { return static_cast<py::ssize_t>(n); }

/// The compared fields of workbench.compare: {"cells": {column: array}, "nodes": {...}, "lines":
/// {name: {column: array}}}, each column rows x components (1D when one component); empty tables
/// (a PBD comparison has no cells) left out.
py::dict compared_fields_dict(compare::ComparedFields&& fields);

/// Every field of agent::kStateFields into `out` by its name, rows (agents or nodes) x components
/// (1D when one), int32 for an integer field; and "diagnostics" (agent::Diagnostics by name).
void add_state_fields(py::dict& out, const agent::AgentState& state, int dim);

/// workbench.agent_fields(): agent::kStateFields, one dict per row.
py::list state_fields_list();

}  // namespace workbench_python
