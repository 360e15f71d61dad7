#pragma once
// chordae.vtp: a chordae network as a VTK line set for ParaView. Point array PointKind
// (0 papillary tip, 1 branch, 2 insertion); line arrays ChordType (0 primary, 1 secondary,
// 2 strut), RestLength_mm, Length_mm and, for a simulated state, Tension_N.
#include <filesystem>
#include <vector>

#include "valve/chordae/chordae_network.hpp"

namespace valve {

/// `positions`: one row per network point (the network's own positions if null).
void write_chordae_vtp(const std::filesystem::path& path, const ChordaeNetwork& network, const MatX3* positions = nullptr,
                       const std::vector<double>* tension = nullptr);

}  // namespace valve
