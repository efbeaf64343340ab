// Per-particle contact-history slots of fix wheel/cosim, keyed by contact feature.
//
// A particle may touch the wheel in several places at once (a lug face and the rim in a groove),
// so each particle owns a few slots, each holding the history of one contact. A slot is found
// again next step by the contact's feature key (face, edge or vertex of the wheel mesh). When a
// contact moves onto a neighbouring feature (across a triangle edge of the tessellated rim), the
// key changes; its history then follows it if the new contact point lies within `handover`
// distance of where the old one was: contacts of one particle are at least about a radius apart,
// so this never confuses two contacts. Plain C++ (no LIGGGHTS), unit-tested.
#ifndef WHEELSIM_CONTACT_SLOTS_H
#define WHEELSIM_CONTACT_SLOTS_H

#include "contact_law.h"

#include <Eigen/Core>

#include <cstdint>

namespace wheelsim {

/// One slot; an empty slot has key < 0. Stored as kSlotDoubles contiguous doubles per slot.
struct ContactSlot {
  double key;        ///< feature key of the contact (SurfaceContact::feature_key), < 0 = empty
  double point_m[3]; ///< contact point in the wheel frame [m], for the hand-over test
  contact::ContactHistory history;
};
constexpr int kSlotDoubles = 4 + contact::ContactHistory::kSize;
static_assert(sizeof(ContactSlot) == kSlotDoubles * sizeof(double), "ContactSlot must be flat");

/// A contact found this step, as the slot matcher needs it.
struct SlotQuery {
  std::int64_t key;
  Eigen::Vector3d point_m; ///< contact point, wheel frame [m]
};

/// Matches this step's contacts to a particle's slots.
/// - `slot_of[j]` receives the slot index holding contact j's history, or -1 when no slot is
///   free (the contact then gets a fresh history each step; the caller counts these).
/// - Same key first; then an unmatched slot whose point is within `handover_m` (nearest first).
/// - If `update` (a normal step): matched slots take the new key and point, unmatched contacts
///   get a free slot with zero history, slots no contact claimed are emptied. If not (LIGGGHTS'
///   setup, where history must not advance): slots are left untouched, and contacts without a
///   matching slot get -1.
void match_contact_slots(ContactSlot *slots, int nslots, const SlotQuery *contacts, int ncontacts,
                         double handover_m, bool update, int *slot_of);

/// Empties all slots of a particle (no contact this step).
inline void clear_contact_slots(ContactSlot *slots, int nslots) {
  for (int s = 0; s < nslots; ++s)
    slots[s].key = -1.0;
}

} // namespace wheelsim

#endif
