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
/// The build type and compiler flags ("Release -O3 -DNDEBUG"; " sanitize", " fuzz" for
/// those trees): with the commit and the compiler, what decides the floating-point bits.
const char* build_flags();

}  // namespace pronk
