// Stand-in for LIGGGHTS' generated style_rolling_model.h (not installed by Debian's
// libliggghts-dev): the models precompiled_contact_models.cpp instantiates. Each model header gives
// its own id (e.g. ROLLING_MODEL(ROLLING_CDT,cdt,1)), the same the library was built with. No
// include guard: LIGGGHTS reads this file once per X_MODEL macro definition. See README.md here.
#include "rolling_model_cdt.h"
// wheelsim's own models (liggghts_fix/): the keywords are registered by
// precompiled_contact_models.cpp
#include "rolling_model_epsdt.h"
#include "rolling_model_krot.h"
