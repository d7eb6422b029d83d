// Adam (Kingma & Ba), as torch.optim.Adam steps the reference trainer's parameter groups, one
// parameter float at a time. preprocess_backward.comp and sh_backward.comp call it where they find
// each gradient, so the gradients never go to memory: that saves an array the size of the
// parameters, and a pass that reads four such arrays and writes three. Every parameter steps
// every iteration, also with a zero gradient (its moments decay), as torch's dense Adam does.
// A step is split into loading a float's state and storing its update so that a thread can load
// several floats' states before it stores any: the compiler may not move a load above a store
// through another buffer reference (they might alias), so one float at a time would wait out a
// memory round trip per float.
#ifndef VKSPLAT_TRAIN_ADAM_GLSL
#define VKSPLAT_TRAIN_ADAM_GLSL

#include "shaders/train/adam_step.h"

struct AdamState {
    float param, m, v;
};

AdamState adam_load(AdamSettings s, Floats params, uint at) {
    return AdamState(params.v[at], s.first_moment.v[at], s.second_moment.v[at]);
}

// One float's step from its state and gradient.
AdamState adam_step(AdamSettings s, AdamState state, float g, float learning_rate) {
    const float m = s.beta1 * state.m + (1.0 - s.beta1) * g;
    const float v = s.beta2 * state.v + (1.0 - s.beta2) * g * g;
    const float step = (m / s.bias_correction1) / (sqrt(v / s.bias_correction2) + s.epsilon);
    return AdamState(state.param - learning_rate * step, m, v);
}

void adam_store(AdamSettings s, Floats params, uint at, AdamState state, float g, float learning_rate) {
    const AdamState next = adam_step(s, state, g, learning_rate);
    s.first_moment.v[at] = next.m;
    s.second_moment.v[at] = next.v;
    params.v[at] = next.param;
}

#endif
