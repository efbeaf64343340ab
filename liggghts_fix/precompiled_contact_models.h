// Contact-model combinations of `pair_style gran` and `fix wall/gran` that liggghts-wheel compiles
// itself, beyond the ones Debian's LIGGGHTS 3.8 was built with.
//
// LIGGGHTS instantiates one class per combination of normal, tangential, cohesion, rolling and
// surface model it was told to optimise at build time (its "whitelist"); any other combination
// runs a generic class that picks each model at run time, "increasing runtime by up to 20 %" (its
// warning). The soils with cohesion and rolling friction (`model hertz tangential history cohesion
// sjkr rolling_friction cdt`: dry_sand, upland_sand, clayey_loam, validation_bed) are such a
// combination in Debian's build. LIGGGHTS' own style factory is a run-time table keyed by the
// combination's hash code, and the classes are header templates: registering our instantiation of
// the combination makes pair_style gran and wall/gran pick it instead of the generic class. The
// physics is the same code (the model headers LIGGGHTS installs); docs/liggghts-wheel.md.
//
// The same mechanism adds wheelsim's own rolling models `rolling_friction krot` and `epsdt`
// (rolling_model_krot.h, rolling_model_epsdt.h) and tangential model `tangential history_adhesive`
// (tangential_model_history_adhesive.h): their keywords and combinations exist only through
// this registration (with WHEELSIM_GENERIC_CONTACT_MODELS=1, LIGGGHTS rejects the keywords).
#ifndef WHEELSIM_PRECOMPILED_CONTACT_MODELS_H
#define WHEELSIM_PRECOMPILED_CONTACT_MODELS_H

#include <string>
#include <vector>

namespace wheelsim {

/// Environment variable that switches the registration off (value "1"): every combination then
/// runs LIGGGHTS' own choice (whitelisted or generic), for comparisons and the benchmark.
inline constexpr const char *kGenericContactModelsEnv = "WHEELSIM_GENERIC_CONTACT_MODELS";

/// The combinations this build adds, as `pair_style gran` keywords (e.g. "model hertz tangential
/// history cohesion sjkr rolling_friction cdt"), in registration order.
std::vector<std::string> precompiled_contact_model_names();

/// Adds the keywords `krot` and `epsdt` to LIGGGHTS' rolling models, `history_adhesive` to its
/// tangential models, and every combination to its pair and wall style factories, unless the
/// environment variable above is "1" (a value other than "1", "0" or empty: std::runtime_error
/// naming it). Returns the number registered (0 when switched
/// off). Call before the input is read. Should a later LIGGGHTS build include one of them, its
/// factory replaces the library's entry and prints "Style collision detected" on stderr.
int register_precompiled_contact_models();

} // namespace wheelsim

#endif
