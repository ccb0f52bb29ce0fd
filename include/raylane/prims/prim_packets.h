// Every kind's SIMD kernel (intersect_packet), for the traversals of the per-ISA translation
// units. Lane code: baseline code includes prim_list.h, never this.
#pragma once

#include "raylane/prims/box_packet.h"
#include "raylane/prims/csg_packet.h"
#include "raylane/prims/cylinder_packet.h"
#include "raylane/prims/moving_sphere_packet.h"
#include "raylane/prims/sdf_packet.h"
#include "raylane/prims/sphere_packet.h"
#include "raylane/prims/triangle_packet.h"
