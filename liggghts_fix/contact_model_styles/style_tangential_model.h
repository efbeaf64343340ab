// Stand-in for LIGGGHTS' generated style_tangential_model.h (not installed by Debian's
// libliggghts-dev): the models precompiled_contact_models.cpp instantiates. Each model header gives
// its own id (e.g. ROLLING_MODEL(ROLLING_CDT,cdt,1)), the same the library was built with. No
// include guard: LIGGGHTS reads this file once per X_MODEL macro definition. See README.md here.
#include "tangential_model_history.h"
// wheelsim's own model (liggghts_fix/): the keyword is registered by precompiled_contact_models.cpp
#include "tangential_model_history_adhesive.h"
