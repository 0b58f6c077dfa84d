#pragma once
// A fixture for the include-map check: the driver must not include the MPM solver.
#include "mpm/explicit/explicit_solver.hpp"
