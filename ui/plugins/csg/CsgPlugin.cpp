#include "CsgPlugin.h"
