#pragma once
// How often the machine takes the calling thread's core away for a while, measured where the tick is
// timed: a thread reads the clock back to back and counts the gaps. On a VM these include the host's
// preemption that its steal counter does not report (this one's reports none), and the guest's own
// timer and device interrupts. A tick of mean duration T is hit with a probability near
// per_s_over_5us * T: where that nears 0.1%, p99.9 shows the machine, not the tick.
namespace palpate::cli {

struct HostInterruptions {
  double seconds = 0.0;         // measured for
  double per_s_over_5us = 0.0;  // gaps of 5 us or more, per second
  double per_s_over_20us = 0.0;
  double lost_us_per_s = 0.0;  // time in gaps of 5 us or more, per second
  double longest_us = 0.0;
};

// Spins on the calling thread for `seconds`.
HostInterruptions measure_host_interruptions(double seconds);

}  // namespace palpate::cli
