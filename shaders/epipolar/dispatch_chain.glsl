// Indirect dispatches sized by the pass that produces their work, not by a one-thread argument
// pass of their own: the last workgroup of the producer to finish sees every group's appends and
// writes the next pass's VkDispatchIndirectCommand. Each dispatch has its own arguments in the
// march list's header, so no pass writes the arguments its own dispatch was read from.
#ifndef TYNDALL_EPIPOLAR_DISPATCH_CHAIN_GLSL
#define TYNDALL_EPIPOLAR_DISPATCH_CHAIN_GLSL

// march.comp's threads per entry (specialised like the march): a round's groups take
// TYN_EPIPOLAR_MARCH_GROUP / TYN_MARCH_PARTS entries each.
layout(constant_id = 2) const uint TYN_MARCH_PARTS = 1u;

// MarchList::groups_done's counters, one per producing pass.
const uint TYN_DONE_SETUP = 0u;
const uint TYN_DONE_SHADOW_TEST = 1u;
const uint TYN_DONE_REFINE_INTENSITY = 2u;
const uint TYN_DONE_UNWARP = 3u;

// Called by every invocation of the group, in uniform control flow, after the group's last append.
// True in invocation 0 of the dispatch's last group to finish: the buffer barriers order each
// group's appends before its count, and this group's reads after it.
bool tyn_last_group(uint pass) {
  memoryBarrierBuffer();
  barrier();
  bool last = false;
  if (gl_LocalInvocationIndex == 0u) {
    uint groups = gl_NumWorkGroups.x * gl_NumWorkGroups.y * gl_NumWorkGroups.z;
    last = atomicAdd(groups_done[pass], 1u) + 1u == groups;
    memoryBarrierBuffer();
  }
  return last;
}

// Starts march round `round` (0 or 1) over the entries listed since the previous round started:
// [march_round_end, march_count) becomes [march_first, march_round_end). At most
// TYN_EPIPOLAR_MAX_GROUPS groups: march.comp's groups stride over the rest.
void tyn_start_march_round(uint round) {
  uint count = atomicAdd(march_count, 0u);
  march_first = march_round_end;
  march_round_end = count;
  uint per_group = TYN_EPIPOLAR_MARCH_GROUP / TYN_MARCH_PARTS;
  round_groups[3u * round] = min((count - march_first + per_group - 1u) / per_group, TYN_EPIPOLAR_MAX_GROUPS);
  round_groups[3u * round + 1u] = 1u;
  round_groups[3u * round + 2u] = 1u;
}

#endif
