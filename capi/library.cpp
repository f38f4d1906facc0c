// Library information: version, status names, the dlopen function table (placeholder, being written).
#include "kairos/kairos.h"
extern "C" uint32_t kairos_version(void) { return KAIROS_VERSION_NUMBER; }
