// Convenience header: the whole wheelsim geometry library.
#pragma once

#include "wheelsim/geometry/mass_properties.h"
#include "wheelsim/geometry/mesh_check.h"
#include "wheelsim/geometry/mesh_error.h"
#include "wheelsim/geometry/mesh_io.h"
#include "wheelsim/geometry/triangle_mesh.h"
#include "wheelsim/geometry/vertex_welder.h"
