#pragma once
// A file that breaks the include map on purpose (tests/layout/CMakeLists.txt): the implicit solver
// may not include the explicit one.
#include "mpm/explicit/explicit_solver.hpp"
