// SPDX-License-Identifier: MIT
// All of shapestruct's concepts.
#pragma once

#include "shapestruct/core/concepts/alignment_score.hpp"
#include "shapestruct/core/concepts/correspondence_map.hpp"
#include "shapestruct/core/concepts/energy_term.hpp"
#include "shapestruct/core/concepts/linear_operator.hpp"
#include "shapestruct/core/concepts/pairwise_matcher.hpp"
#include "shapestruct/core/concepts/point_set.hpp"
#include "shapestruct/core/concepts/shape_aligner.hpp"
#include "shapestruct/core/concepts/shape_descriptor.hpp"
#include "shapestruct/core/concepts/surface_mesh.hpp"
