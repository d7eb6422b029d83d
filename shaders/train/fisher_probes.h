// The Fisher probes (src/train/fisher_probes.cpp): fisher_probe_signs.comp fills a picture's
// dL/d rgb with random signs, the backward pass turns it into one gradient per Gaussian, and
// fisher_accumulate.comp adds that gradient's outer product over (mean, log-scales) to the
// Gaussian's sum. One thread per pixel or per Gaussian, 256 per workgroup, grid-stride loops.
#ifndef VKSPLAT_TRAIN_FISHER_PROBES_H
#define VKSPLAT_TRAIN_FISHER_PROBES_H

#include "shaders/common/buffers.h"
#include "shaders/train/parameter_layout.h"

SHADER_NAMESPACE_BEGIN(train)

// The upper triangle of the 6x6 sum over (mean x, y, z, log-scale 0, 1, 2), row by row: (0,0),
// (0,1) ... (0,5), (1,1) ... (5,5).
SHADER_CONST(uint, FISHER_FLOATS, 21u)

struct FisherProbeSignsPush {
    Vec4s pixel_grad;  // out: (+-1, +-1, +-1, 0) per pixel
    uint pixels;
    uint seed;         // differs for every probe of every view
};

struct FisherAccumulatePush {
    Floats grads;      // the backward pass's gradients in the parameter layout
    Floats fisher;     // FISHER_FLOATS per Gaussian, added to
    Uints status;      // the step's status: a probe whose frame overflowed (or went non-finite) adds nothing
    uint count;        // Gaussians
};

SHADER_NAMESPACE_END

#endif
