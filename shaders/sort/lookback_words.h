// Look-back words of the sort module's single-pass kernels (scan_lookback.comp,
// radix_scatter_one_sweep.comp): polled while other workgroups write them, so read (relaxed atomic
// loads) and written only by atomics (plain reads, even volatile ones, were seen on lavapipe to be
// re-read between uses, mixing one word's flag with a later word's value); the polls are relaxed
// atomic loads (lego's depth sort on an H100: 0.118 ms, 0.189 with read-modify-write polls).
#ifndef VKSPLAT_SORT_LOOKBACK_WORDS_H
#define VKSPLAT_SORT_LOOKBACK_WORDS_H

#include "shaders/common/buffers.h"

#ifdef __cplusplus
SHADER_NAMESPACE_BEGIN(sort)
BUFFER_REFERENCE(LookbackWords, uint, 4)
SHADER_NAMESPACE_END
#else
layout(buffer_reference, std430, buffer_reference_align = 4) coherent buffer LookbackWords { uint v[]; };
#endif

#endif
