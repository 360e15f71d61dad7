#pragma once
// Where valve finds its data when it runs: beside its executable, laid out as installed,
//   PREFIX/bin/valve-*            the stages
//   PREFIX/share/valve/configs    the presets (materials/*.json)
// The build tree has the same shape (build/stages/, build/tests/ and build/share/valve/configs,
// a link to the source's configs/), so the build and an installed copy anywhere find their
// presets the same way and no path into the source tree is compiled in.
#include <filesystem>

namespace valve {

/// Directory of the running executable (/proc/self/exe); empty if it cannot be read.
std::filesystem::path executable_directory();

/// The presets folder: $VALVE_CONFIG_DIR if set; else EXE_DIR/../share/valve/configs if it
/// exists (a stage, installed or in the build tree); else the configured install prefix's
/// (a program of one's own linked against an installed libvalve).
std::filesystem::path config_directory();

}  // namespace valve
