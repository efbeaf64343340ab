// The list of contact models of fix wheel/cosim: one line per model, by the fix keyword that
// selects it. Each entry is X(Enumerator, name) where `name` is both the model's header
// models/<name>.h and its namespace wheelsim::contact::<name>, which declares the model's `spec`
// (keyword, LIGGGHTS properties, switches, time-step rule: contact_model.h) and its force
// kernel `apply` (see docs/extending.md, "Adding a contact model").
//
// The lists generate the enums of ContactSettings (contact_law.h), the descriptor table
// (contact_models.cpp) and the per-contact dispatch (a switch over the enum in contact_law.cpp:
// no virtual call, the kernels are inlined).
//
// This file is read twice: once for the lists (by contact_law.h), and once more with
// WHEELSIM_CONTACT_MODEL_HEADERS defined, for the model headers (by the two .cpp files above).
// Adding a model: its header, then one X(...) line and one #include below.
#ifndef WHEELSIM_CONTACT_MODEL_LIST_H
#define WHEELSIM_CONTACT_MODEL_LIST_H

/// `model ...`: the normal force law.
#define WHEELSIM_NORMAL_MODELS(X) X(Hertz, normal_hertz) X(Eepa, normal_eepa)
/// `tangential ...`: the tangential force law.
#define WHEELSIM_TANGENTIAL_MODELS(X)                                                              \
  X(History, tangential_history) X(HistoryAdhesive, tangential_history_adhesive)
/// `cohesion ...`: a normal force added to the normal law's.
#define WHEELSIM_COHESION_MODELS(X) X(Off, cohesion_off) X(Sjkr, cohesion_sjkr)
/// `rolling_friction ...`: rolling resistance (a torque on the particle).
#define WHEELSIM_ROLLING_MODELS(X)                                                                 \
  X(Off, rolling_off)                                                                              \
  X(Epsd2, rolling_epsd2) X(Cdt, rolling_cdt) X(Krot, rolling_krot) X(Epsdt, rolling_epsdt)

#endif

#ifdef WHEELSIM_CONTACT_MODEL_HEADERS
#include "models/cohesion_off.h"
#include "models/cohesion_sjkr.h"
#include "models/normal_eepa.h"
#include "models/normal_hertz.h"
#include "models/rolling_cdt.h"
#include "models/rolling_epsd2.h"
#include "models/rolling_epsdt.h"
#include "models/rolling_krot.h"
#include "models/rolling_off.h"
#include "models/tangential_history.h"
#include "models/tangential_history_adhesive.h"
#endif
