#pragma once
// The version and source commit this tool was built from, for the results files. The generated
// header is rewritten by the anyphys_build_info target on every build, only when it changed
// (tools/anyphys/build_info.cmake).
#include "anyphys_build_info.hpp"
