// Guide values of peak particle velocity for damage to buildings, read at the dominant
// frequency of the vibration, and the ratio PPV / guide value (>= 1: the guide value is
// reached). Velocities in m/s (the standards quote mm/s), frequencies in Hz.
//
// DIN 4150-3 (1999, values unchanged in the 2016 edition), Table 1, short-term vibration at the
// foundation, the largest of the three components (x, y, z), 1 Hz to 100 Hz:
//   line 1, commercial / industrial buildings:    20 mm/s (1-10 Hz), 20 -> 40 (10-50), 40 -> 50
//   (50-100) line 2, dwellings and similar:                  5 mm/s,             5 -> 15,        15
//   -> 20 line 3, particularly sensitive (listed) ones:   3 mm/s,             3 -> 8,          8 ->
//   10
// linearly interpolated in frequency within each band, as drawn in the standard's Figure 1;
// above 100 Hz the 100 Hz value (the standard: "at least" it), below 1 Hz the 1 Hz value.
//
// BS 7385-2 (1993), Table 1, transient vibration guide values for cosmetic damage, at the base
// of the building, peak component particle velocity:
//   line 1, reinforced or framed structures, industrial and heavy commercial: 50 mm/s at 4 Hz
//           and above;
//   line 2, unreinforced or light framed structures, residential or light commercial:
//           15 mm/s at 4 Hz rising linearly to 20 mm/s at 15 Hz, then to 50 mm/s at 40 Hz and
//           above; below 4 Hz the table's note limits the displacement to 0.6 mm (zero to
//           peak), returned here as the velocity 2 pi f 0.6 mm (15.08 mm/s at 4 Hz, so the two
//           parts meet within 0.53 %).
//   Below 4 Hz line 1 is taken as 50 mm/s (the table gives no lower limit for it).
//   For continuous vibration that may amplify by resonance, BS 7385-2 reduces these by up to
//   50 %; that judgement is the user's (multiply the guide value by the factor).
//
// Sources: the DIN 4150-3 values as the vibration literature quotes them, gathered without the
// standard's text (docs/post-processing.md, "Guide values"), and as transcribed, identically,
// in public monitoring software (e.g. the DIN 4150-3:2016 Table 1 and BS 7385-2:1993 Table 1
// tables of the receiver-criteria module found in the public code index;
// BS 7385-2's line-2 interpolation written there as 15 + 5/11 (f - 4) and 20 + 30/25 (f - 15)).
// The standards themselves are not freely available: a user with the published text should
// confirm the values before relying on them for an assessment.
#pragma once

#include <string>

namespace rumble::post {

enum class Din4150Line { kCommercial = 1, kDwelling = 2, kSensitive = 3 };
enum class Bs7385Line { kReinforced = 1, kUnreinforced = 2 };

/// DIN 4150-3 Table 1 guide value [m/s] at frequency f [Hz] (> 0, finite).
double din4150_3_guide(Din4150Line line, double f);

/// BS 7385-2 Table 1 guide value [m/s] at frequency f [Hz] (> 0, finite).
double bs7385_2_guide(Bs7385Line line, double f);

/// A peak set against a guide value.
struct GuideCheck {
  double guide = 0.0;  // m/s
  double ratio = 0.0;  // ppv / guide [-]
};

GuideCheck check_din4150_3(Din4150Line line, double ppv, double f);
GuideCheck check_bs7385_2(Bs7385Line line, double ppv, double f);

/// "DIN 4150-3 line 2" and the like, for tables.
std::string name(Din4150Line line);
std::string name(Bs7385Line line);

}  // namespace rumble::post
