#pragma once
// A stage as a 3D Slicer CLI module: the module description (SlicerExecutionModel XML) that
// Slicer reads from `<stage> --xml` to build the module's panel and its command line.
#include <string>
#include <vector>

namespace valve {

/// The description of `program` from its --help text (title, prose, positional arguments and
/// each option's placeholder, e.g. `[--denoise gaussian|median|none]`) and from the options its
/// command line accepts (`flags` take a value, `switches` none), so that it offers exactly what
/// the stage accepts. Options are strings left empty by default: Slicer then leaves them off the
/// command line and the stage's own defaults apply. Slicer gets progress through the
/// hidden --progress slicer.
std::string slicer_cli_xml(const std::string& program, const std::string& usage, const std::vector<std::string>& flags,
                           const std::vector<std::string>& switches);

}  // namespace valve
