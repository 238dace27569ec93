// The program's version, "PROJECT_VERSION+git-describe" of the commit built (written at
// every build, cmake/version.cmake); every output records it. Defined in a file generated
// from core/version.cc.in, so a new commit recompiles one file instead of every file that
// sees a compile definition.
#pragma once

namespace moorsim {

extern const char* const kVersion;

}  // namespace moorsim
