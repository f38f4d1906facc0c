// SPDX-License-Identifier: MIT
// Fuzz target: shape construction from arbitrary bytes. Every constructor and combinator, with
// each result checked against an independent model of its support function (fuzz_support.hpp).
#include <cstddef>
#include <cstdint>

#include "fuzz_support.hpp"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    kfuzz::Input in(data, size);
    kfuzz::ShapeBuilder builder(in, /*max_depth=*/3, /*thorough=*/true);
    // A few shapes per input; later composites may reuse earlier ones as parts.
    for (int i = 0; i < 8 && (i == 0 || in.remaining() > 0); ++i) {
        std::optional<kfuzz::Built> b = builder.build();
        if (b && in.rare(4)) {
            // Extra references taken and given back leave the shape as it was.
            kairos_shape_retain(b->shape.get());
            kairos_shape_retain(b->shape.get());
            kairos_shape_release(b->shape.get());
            kairos_shape_release(b->shape.get());
            kfuzz::check_shape(b->shape.get(), *b->model, in);
        }
    }
    return 0;
}
