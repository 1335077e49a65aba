#pragma once
// The column rule set's layers across the beam (agent/columns.h): what column_fields adds to the
// columns' Navier and Jourawski stresses under a clamp, the clamp's restraint and the loads' push
// (column_layers.cc), and the columns' agents they and columns.cc read.
#include <agent/columns.h>

#include <cstddef>
#include <vector>

namespace agent {

/// Each column's agents (column i: agents[start[i], start[i + 1])), sorted along t (a dense 2D
/// grid's id order is that order: sorted only when not), with their coordinates along t (rows)
/// and, in 3D, along w (read once: a slot's coordinates cost divisions).
struct ColumnAgents {
  std::vector<std::size_t> start, agents;
  std::vector<int> rows, across;
};

/// The clamp's layer: sigma_t (and in 3D sigma_w) of the clamp's restraint across the beam, decaying
/// away from it; nothing unless the columns are held by a clamp.
void clamp_layer(const Grid& g, const Material& material, const Columns& c, const ColumnAgents& ca, TransferResults& out);

/// The clamp's shears across the beam (3D): tau_aw and an addition to tau_at from the clamp's layer
/// by equilibrium, zero at the free end; nothing between supports or in 2D.
void clamp_shears(const Grid& g, const Columns& c, const ColumnAgents& ca, TransferResults& out);

/// The loads' layer under a clamp (2D): each push on a face across t spread into the section;
/// nothing between supports or in 3D.
void load_layer(const Grid& g, const Columns& c, const ColumnAgents& ca, const std::vector<EntryLoad>& loads, TransferResults& out);

}  // namespace agent
