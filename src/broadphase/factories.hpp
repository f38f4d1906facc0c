// SPDX-License-Identifier: MIT
// One factory per concrete broad phase, for BroadPhase::create; the classes stay inside their
// files. Internal to broadphase/ (namespace broadphase_detail).
#pragma once

#include <memory>

#include "broadphase/broadphase.hpp"

namespace kairos::broadphase_detail {

std::unique_ptr<BroadPhase> make_spacetime_sap();      // SpacetimeSap (spacetime_sap.cpp)
std::unique_ptr<BroadPhase> make_global_sap();         // SpacetimeSapGlobal (research/, when built)
std::unique_ptr<BroadPhase> make_queued_sap();         // SpacetimeSapQueued (research/)
std::unique_ptr<BroadPhase> make_encapsulating_sap();  // EncapsulatingSap (reference.cpp)
std::unique_ptr<BroadPhase> make_brute_force();        // BruteForce (reference.cpp)

}  // namespace kairos::broadphase_detail
