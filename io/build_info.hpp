// Provenance of the running build, recorded in every output (summary.json,
// design.json, bench.json, map results). Defined in a source file CMake
// generates at configure time (cmake/build_info.cpp.in), so a new commit
// recompiles one file, not the library.
#pragma once

namespace pronk {

/// The project version (CMake's PROJECT_VERSION).
const char* version();
/// The short git commit the build was configured at ("unknown" outside git).
/// CMake re-configures when HEAD or its branch moves.
const char* git_commit();

}  // namespace pronk
