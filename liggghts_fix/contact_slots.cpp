#include "contact_slots.h"

namespace wheelsim {

void match_contact_slots(ContactSlot *slots, int nslots, const SlotQuery *contacts, int ncontacts,
                         double handover_m, bool update, int *slot_of) {
  constexpr int kMaxSlots = 8;
  bool claimed[kMaxSlots] = {false};
  for (int j = 0; j < ncontacts; ++j) {
    slot_of[j] = -1;
    for (int s = 0; s < nslots; ++s)
      if (!claimed[s] && slots[s].key >= 0.0 &&
          static_cast<std::int64_t>(slots[s].key) == contacts[j].key) {
        slot_of[j] = s;
        claimed[s] = true;
        break;
      }
  }
  // Hand-over: nearest unclaimed occupied slot within reach.
  for (int j = 0; j < ncontacts; ++j) {
    if (slot_of[j] >= 0)
      continue;
    int best = -1;
    double best_d2 = handover_m * handover_m;
    for (int s = 0; s < nslots; ++s) {
      if (claimed[s] || slots[s].key < 0.0)
        continue;
      const Eigen::Vector3d p(slots[s].point_m[0], slots[s].point_m[1], slots[s].point_m[2]);
      const double d2 = (p - contacts[j].point_m).squaredNorm();
      if (d2 <= best_d2) {
        best = s;
        best_d2 = d2;
      }
    }
    if (best >= 0) {
      slot_of[j] = best;
      claimed[best] = true;
    }
  }
  if (!update)
    return;
  for (int s = 0; s < nslots; ++s)
    if (!claimed[s])
      slots[s].key = -1.0;
  for (int j = 0; j < ncontacts; ++j) {
    if (slot_of[j] < 0) {
      for (int s = 0; s < nslots; ++s)
        if (!claimed[s]) {
          slot_of[j] = s;
          claimed[s] = true;
          slots[s].history.reset();
          break;
        }
      if (slot_of[j] < 0)
        continue; // all slots taken
    }
    ContactSlot &slot = slots[slot_of[j]];
    slot.key = static_cast<double>(contacts[j].key);
    for (int k = 0; k < 3; ++k)
      slot.point_m[k] = contacts[j].point_m[k];
  }
}

} // namespace wheelsim
