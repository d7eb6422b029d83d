// Moving to shaders/common/buffers.h (shaders/README.md); kept while passes move module by module.
#include "shaders/common/buffers.h"
