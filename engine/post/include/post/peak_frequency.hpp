// The frequency of the half cycle that holds a record's peak, from its zero crossings: the
// zero-crossing frequency at the peak that vibration monitors give and that the DIN 4150-3 and
// BS 7385-2 guide values are read at (docs/post-processing.md, "Dominant frequency"). It belongs
// to the event, not to the record: a spectrum's largest bin moves with the record's length
// (ending a record at 0.45 s instead of 0.5 s moved it from 39 Hz to 2 Hz and the DIN 4150-3
// ratio from 1.26 to 2.81).
#pragma once

#include <cstddef>
#include <span>

namespace rumble::post {

/// f = 1 / (2 (t_after - t_before)) [Hz] for samples v at spacing dt [s], t_before and t_after
/// the sign changes either side of sample `peak` (linearly interpolated between samples); with
/// one side reaching the record's end uncrossed, 1 / (4 |t_cross - t_peak|) (a quarter period
/// from the peak to its zero). NaN when neither side crosses zero or v[peak] is 0 or not finite.
double peak_half_cycle_frequency(std::span<const double> v, std::size_t peak, double dt);

}  // namespace rumble::post
