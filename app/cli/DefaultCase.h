#pragma once
// The CLI's view of the bundled default case (thin re-export of modules/ream).
#include "reamsim/ream/DefaultCase.h"
