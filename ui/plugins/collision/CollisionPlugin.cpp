#include "CollisionPlugin.h"
