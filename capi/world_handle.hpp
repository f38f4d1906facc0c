// SPDX-License-Identifier: MIT
// The object behind the C API's kairos_world handle (capi/world.cpp; the batches borrow its
// threads, capi/batch.cpp).
#pragma once

#include <vector>

#include "kairos/kairos.h"
#include "world/world.hpp"

// The core world plus what the C API hands out by pointer.
struct kairos_world {
    explicit kairos_world(const kairos::WorldSettings& settings) : core(settings) {}
    kairos::World core;
    std::vector<kairos_contact> contacts;  // the core's contacts in C layout, valid until the next step
};
