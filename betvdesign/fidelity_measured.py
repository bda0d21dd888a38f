"""Measured trust limits and costs of the fidelity ladder (GENERATED, do not edit).

Regenerate: ``python benchmarks/work_precision.py --ladder``
(betvdesign.bench.ladder.measure). Read by betvdesign.fidelity.
"""

# fmt: off
MEASURED = {'costs_cpu_s': {'full': 0.0002283200000001706,
                 'lambda': 1.1619999997769526e-06,
                 'periodic': 0.001196401000000069,
                 'rigid': 8.879200000011522e-05,
                 'vertical': 5.4851999999883105e-05},
 'full_cycles': 100,
 'lambda': {'agreement_reported_by_study': 0.9774436090225563,
            'bands': [{'hi': 0.1, 'lo': 0.0, 'mispredicted': 9, 'points': 36},
                      {'hi': 0.2, 'lo': 0.1, 'mispredicted': 11, 'points': 49},
                      {'hi': 0.5, 'lo': 0.2, 'mispredicted': 0, 'points': 179},
                      {'hi': 1.0, 'lo': 0.5, 'mispredicted': 0, 'points': 602},
                      {'hi': 2.0, 'lo': 1.0, 'mispredicted': 0, 'points': 47},
                      {'hi': None, 'lo': 2.0, 'mispredicted': 4, 'points': 151}],
            'beta_bins': [0.1, 0.3, 0.75, 1.25, 1.5],
            'converged': 1064,
            'elapsed_s': 1.6937670540010004,
            'grid': {'alpha': [0.1, 0.5, 1.0, 1.5, 2.0, 2.5, 3.0, 3.5, 4.0],
                     'beta': [0.1, 0.5, 1.0, 1.5],
                     'kappa': [0.1, 0.4],
                     'varpi': [0.5,
                               0.6,
                               0.7,
                               0.8,
                               0.9,
                               1.0,
                               1.1,
                               1.2,
                               1.3,
                               1.4,
                               1.5,
                               1.6,
                               1.7,
                               1.8,
                               1.9,
                               2.0]},
            'mispredicted': 24,
            'mispredictions': [{'alpha': 0.1,
                                'beta': 0.1,
                                'delta_s': 0.007965345947923932,
                                'kappa': 0.1,
                                'lam': 39.836363636363636,
                                'mode': 'push',
                                'varpi': 0.5},
                               {'alpha': 0.1,
                                'beta': 0.1,
                                'delta_s': 0.239718122457607,
                                'kappa': 0.4,
                                'lam': 39.48571428571428,
                                'mode': 'push',
                                'varpi': 0.5},
                               {'alpha': 0.1,
                                'beta': 0.1,
                                'delta_s': 0.14200092375294388,
                                'kappa': 0.4,
                                'lam': 27.420634920634917,
                                'mode': 'push',
                                'varpi': 0.6},
                               {'alpha': 0.5,
                                'beta': 0.1,
                                'delta_s': 0.10522829081530678,
                                'kappa': 0.1,
                                'lam': 3.998144712430427,
                                'mode': 'push',
                                'varpi': 0.7},
                               {'alpha': 3.5,
                                'beta': 1.5,
                                'delta_s': 3.9667042499229384,
                                'kappa': 0.4,
                                'lam': 1.1861471861471862,
                                'mode': 'push',
                                'varpi': 0.5},
                               {'alpha': 3.0,
                                'beta': 0.1,
                                'delta_s': 0.6074450831528828,
                                'kappa': 0.1,
                                'lam': 1.1696969696969697,
                                'mode': 'push',
                                'varpi': 0.5},
                               {'alpha': 1.5,
                                'beta': 0.1,
                                'delta_s': -9.489980038904537,
                                'kappa': 0.4,
                                'lam': 0.8407738095238093,
                                'mode': 'pull',
                                'varpi': 0.8},
                               {'alpha': 3.5,
                                'beta': 1.5,
                                'delta_s': 0.9916760624806487,
                                'kappa': 0.1,
                                'lam': 1.1566312475403382,
                                'mode': 'push',
                                'varpi': 0.5},
                               {'alpha': 3.5,
                                'beta': 1.0,
                                'delta_s': 2.019994593198627,
                                'kappa': 0.1,
                                'lam': 1.1428571428571428,
                                'mode': 'push',
                                'varpi': 0.5},
                               {'alpha': 3.5,
                                'beta': 1.0,
                                'delta_s': 8.079978372794397,
                                'kappa': 0.4,
                                'lam': 1.1428571428571428,
                                'mode': 'push',
                                'varpi': 0.5},
                               {'alpha': 2.5,
                                'beta': 1.5,
                                'delta_s': 4.94463746359448,
                                'kappa': 0.4,
                                'lam': 1.141173641173641,
                                'mode': 'push',
                                'varpi': 0.6},
                               {'alpha': 2.5,
                                'beta': 1.5,
                                'delta_s': 0.11883649180780459,
                                'kappa': 0.1,
                                'lam': 1.1206764615855525,
                                'mode': 'push',
                                'varpi': 0.6},
                               {'alpha': 3.5,
                                'beta': 0.5,
                                'delta_s': 3.0483131239165457,
                                'kappa': 0.1,
                                'lam': 1.1180637544273908,
                                'mode': 'push',
                                'varpi': 0.5},
                               {'alpha': 2.5,
                                'beta': 1.0,
                                'delta_s': 0.8213236486418969,
                                'kappa': 0.1,
                                'lam': 1.1111111111111112,
                                'mode': 'push',
                                'varpi': 0.6},
                               {'alpha': 2.5,
                                'beta': 1.0,
                                'delta_s': 7.754586090931031,
                                'kappa': 0.4,
                                'lam': 1.1111111111111112,
                                'mode': 'push',
                                'varpi': 0.6},
                               {'alpha': 2.5,
                                'beta': 0.5,
                                'delta_s': 1.5238108054760087,
                                'kappa': 0.1,
                                'lam': 1.0938934802571167,
                                'mode': 'push',
                                'varpi': 0.6},
                               {'alpha': 3.5,
                                'beta': 0.5,
                                'delta_s': 12.19325249566623,
                                'kappa': 0.4,
                                'lam': 1.0649350649350648,
                                'mode': 'push',
                                'varpi': 0.5},
                               {'alpha': 2.0,
                                'beta': 0.1,
                                'delta_s': -11.49051808243727,
                                'kappa': 0.1,
                                'lam': 0.9369202226345085,
                                'mode': 'pull',
                                'varpi': 0.7},
                               {'alpha': 2.5,
                                'beta': 0.5,
                                'delta_s': 10.564534718267632,
                                'kappa': 0.4,
                                'lam': 1.0569985569985572,
                                'mode': 'push',
                                'varpi': 0.6},
                               {'alpha': 0.5,
                                'beta': 0.1,
                                'delta_s': -241.8937126676016,
                                'kappa': 0.4,
                                'lam': 0.9548104956268224,
                                'mode': 'pull',
                                'varpi': 1.4},
                               {'alpha': 2.0,
                                'beta': 1.5,
                                'delta_s': 30.825088422282775,
                                'kappa': 0.4,
                                'lam': 1.0424949200459406,
                                'mode': 'push',
                                'varpi': 0.7},
                               {'alpha': 1.5,
                                'beta': 0.1,
                                'delta_s': -23.267265594926656,
                                'kappa': 0.1,
                                'lam': 0.9777462121212118,
                                'mode': 'pull',
                                'varpi': 0.8},
                               {'alpha': 2.0,
                                'beta': 1.0,
                                'delta_s': 32.78653791873466,
                                'kappa': 0.4,
                                'lam': 1.0204081632653064,
                                'mode': 'push',
                                'varpi': 0.7},
                               {'alpha': 0.5,
                                'beta': 0.1,
                                'delta_s': -242.98174385505902,
                                'kappa': 0.1,
                                'lam': 0.9995361781076068,
                                'mode': 'pull',
                                'varpi': 1.4}],
            'not_converged': [{'alpha': 0.1,
                               'beta': 0.1,
                               'kappa': 0.1,
                               'message': 'no contact recurred within 1000 cycles: hits are '
                                          'impulsive only and the slider is not driven (MODEL.md: '
                                          'ϖ beyond about 2); increase max_cycles to look further',
                               'status': 'not_driven',
                               'varpi': 2.0},
                              {'alpha': 0.5,
                               'beta': 0.1,
                               'kappa': 0.1,
                               'message': 'no contact recurred within 1000 cycles: hits are '
                                          'impulsive only and the slider is not driven (MODEL.md: '
                                          'ϖ beyond about 2); increase max_cycles to look further',
                               'status': 'not_driven',
                               'varpi': 2.0},
                              {'alpha': 1.0,
                               'beta': 0.1,
                               'kappa': 0.1,
                               'message': 'unbounded tangential motion: free-flight tangential '
                                          'resonance a·ϖ² = 1 with a = α = 1 at ϖ = 1 (α·ϖ² = 1; '
                                          'stick has a = α(1 + 1/β) = 11). Contact friction '
                                          'cancels at most the fraction ακ/2 = 0.05 < 1 of the '
                                          'resonant drive, so no periodic orbit exists: ζ at the '
                                          'section falls by ≥ π(1 − ακ/2) = 2.98451 per cycle '
                                          '(proven); measured 3.0415 per cycle over 256 cycles, '
                                          'amplitude 781.7 after 257 cycles. Move ϖ or α away '
                                          'from the resonance (α·ϖ² ≠ 1, e.g. by a few %)',
                               'status': 'unbounded',
                               'varpi': 1.0},
                              {'alpha': 1.0,
                               'beta': 0.1,
                               'kappa': 0.1,
                               'message': 'no contact recurred within 1000 cycles: hits are '
                                          'impulsive only and the slider is not driven (MODEL.md: '
                                          'ϖ beyond about 2); increase max_cycles to look further',
                               'status': 'not_driven',
                               'varpi': 2.0},
                              {'alpha': 1.5,
                               'beta': 0.1,
                               'kappa': 0.1,
                               'message': 'no contact recurred within 1000 cycles: hits are '
                                          'impulsive only and the slider is not driven (MODEL.md: '
                                          'ϖ beyond about 2); increase max_cycles to look further',
                               'status': 'not_driven',
                               'varpi': 2.0},
                              {'alpha': 2.0,
                               'beta': 0.1,
                               'kappa': 0.1,
                               'message': 'no contact recurred within 1000 cycles: hits are '
                                          'impulsive only and the slider is not driven (MODEL.md: '
                                          'ϖ beyond about 2); increase max_cycles to look further',
                               'status': 'not_driven',
                               'varpi': 2.0},
                              {'alpha': 2.5,
                               'beta': 0.1,
                               'kappa': 0.1,
                               'message': 'no contact recurred within 1000 cycles: hits are '
                                          'impulsive only and the slider is not driven (MODEL.md: '
                                          'ϖ beyond about 2); increase max_cycles to look further',
                               'status': 'not_driven',
                               'varpi': 2.0},
                              {'alpha': 3.0,
                               'beta': 0.1,
                               'kappa': 0.1,
                               'message': 'no contact recurred within 1000 cycles: hits are '
                                          'impulsive only and the slider is not driven (MODEL.md: '
                                          'ϖ beyond about 2); increase max_cycles to look further',
                               'status': 'not_driven',
                               'varpi': 2.0},
                              {'alpha': 3.5,
                               'beta': 0.1,
                               'kappa': 0.1,
                               'message': 'no contact recurred within 1000 cycles: hits are '
                                          'impulsive only and the slider is not driven (MODEL.md: '
                                          'ϖ beyond about 2); increase max_cycles to look further',
                               'status': 'not_driven',
                               'varpi': 2.0},
                              {'alpha': 4.0,
                               'beta': 0.1,
                               'kappa': 0.1,
                               'message': 'unbounded tangential motion: free-flight tangential '
                                          'resonance a·ϖ² = 1 with a = α = 4 at ϖ = 0.5 (α·ϖ² = '
                                          '1; stick has a = α(1 + 1/β) = 44). Contact friction '
                                          'cancels at most the fraction ακ/2 = 0.2 < 1 of the '
                                          'resonant drive, so no periodic orbit exists: ζ at the '
                                          'section falls by ≥ π(1 − ακ/2) = 2.51327 per cycle '
                                          '(proven); measured 2.51329 per cycle over 256 cycles, '
                                          'amplitude 645.9 after 257 cycles. Move ϖ or α away '
                                          'from the resonance (α·ϖ² ≠ 1, e.g. by a few %)',
                               'status': 'unbounded',
                               'varpi': 0.5},
                              {'alpha': 4.0,
                               'beta': 0.1,
                               'kappa': 0.1,
                               'message': 'no contact recurred within 1000 cycles: hits are '
                                          'impulsive only and the slider is not driven (MODEL.md: '
                                          'ϖ beyond about 2); increase max_cycles to look further',
                               'status': 'not_driven',
                               'varpi': 2.0},
                              {'alpha': 0.1,
                               'beta': 0.5,
                               'kappa': 0.1,
                               'message': 'no contact recurred within 1000 cycles: hits are '
                                          'impulsive only and the slider is not driven (MODEL.md: '
                                          'ϖ beyond about 2); increase max_cycles to look further',
                               'status': 'not_driven',
                               'varpi': 2.0},
                              {'alpha': 0.5,
                               'beta': 0.5,
                               'kappa': 0.1,
                               'message': 'no contact recurred within 1000 cycles: hits are '
                                          'impulsive only and the slider is not driven (MODEL.md: '
                                          'ϖ beyond about 2); increase max_cycles to look further',
                               'status': 'not_driven',
                               'varpi': 2.0},
                              {'alpha': 1.0,
                               'beta': 0.5,
                               'kappa': 0.1,
                               'message': 'unbounded tangential motion: free-flight tangential '
                                          'resonance a·ϖ² = 1 with a = α = 1 at ϖ = 1 (α·ϖ² = 1; '
                                          'stick has a = α(1 + 1/β) = 3). Contact friction '
                                          'cancels at most the fraction ακ/2 = 0.05 < 1 of the '
                                          'resonant drive, so no periodic orbit exists: ζ at the '
                                          'section falls by ≥ π(1 − ακ/2) = 2.98451 per cycle '
                                          '(proven); measured 3.0415 per cycle over 256 cycles, '
                                          'amplitude 781.7 after 257 cycles. Move ϖ or α away '
                                          'from the resonance (α·ϖ² ≠ 1, e.g. by a few %)',
                               'status': 'unbounded',
                               'varpi': 1.0},
                              {'alpha': 1.0,
                               'beta': 0.5,
                               'kappa': 0.1,
                               'message': 'no contact recurred within 1000 cycles: hits are '
                                          'impulsive only and the slider is not driven (MODEL.md: '
                                          'ϖ beyond about 2); increase max_cycles to look further',
                               'status': 'not_driven',
                               'varpi': 2.0},
                              {'alpha': 1.5,
                               'beta': 0.5,
                               'kappa': 0.1,
                               'message': 'no contact recurred within 1000 cycles: hits are '
                                          'impulsive only and the slider is not driven (MODEL.md: '
                                          'ϖ beyond about 2); increase max_cycles to look further',
                               'status': 'not_driven',
                               'varpi': 2.0},
                              {'alpha': 2.0,
                               'beta': 0.5,
                               'kappa': 0.1,
                               'message': 'no contact recurred within 1000 cycles: hits are '
                                          'impulsive only and the slider is not driven (MODEL.md: '
                                          'ϖ beyond about 2); increase max_cycles to look further',
                               'status': 'not_driven',
                               'varpi': 2.0},
                              {'alpha': 2.5,
                               'beta': 0.5,
                               'kappa': 0.1,
                               'message': 'no contact recurred within 1000 cycles: hits are '
                                          'impulsive only and the slider is not driven (MODEL.md: '
                                          'ϖ beyond about 2); increase max_cycles to look further',
                               'status': 'not_driven',
                               'varpi': 2.0},
                              {'alpha': 3.0,
                               'beta': 0.5,
                               'kappa': 0.1,
                               'message': 'no contact recurred within 1000 cycles: hits are '
                                          'impulsive only and the slider is not driven (MODEL.md: '
                                          'ϖ beyond about 2); increase max_cycles to look further',
                               'status': 'not_driven',
                               'varpi': 2.0},
                              {'alpha': 3.5,
                               'beta': 0.5,
                               'kappa': 0.1,
                               'message': 'no contact recurred within 1000 cycles: hits are '
                                          'impulsive only and the slider is not driven (MODEL.md: '
                                          'ϖ beyond about 2); increase max_cycles to look further',
                               'status': 'not_driven',
                               'varpi': 2.0},
                              {'alpha': 4.0,
                               'beta': 0.5,
                               'kappa': 0.1,
                               'message': 'unbounded tangential motion: free-flight tangential '
                                          'resonance a·ϖ² = 1 with a = α = 4 at ϖ = 0.5 (α·ϖ² = '
                                          '1; stick has a = α(1 + 1/β) = 12). Contact friction '
                                          'cancels at most the fraction ακ/2 = 0.2 < 1 of the '
                                          'resonant drive, so no periodic orbit exists: ζ at the '
                                          'section falls by ≥ π(1 − ακ/2) = 2.51327 per cycle '
                                          '(proven); measured 2.51531 per cycle over 256 cycles, '
                                          'amplitude 646.5 after 257 cycles. Move ϖ or α away '
                                          'from the resonance (α·ϖ² ≠ 1, e.g. by a few %)',
                               'status': 'unbounded',
                               'varpi': 0.5},
                              {'alpha': 4.0,
                               'beta': 0.5,
                               'kappa': 0.1,
                               'message': 'no contact recurred within 1000 cycles: hits are '
                                          'impulsive only and the slider is not driven (MODEL.md: '
                                          'ϖ beyond about 2); increase max_cycles to look further',
                               'status': 'not_driven',
                               'varpi': 2.0},
                              {'alpha': 0.1,
                               'beta': 1.0,
                               'kappa': 0.1,
                               'message': 'no contact recurred within 1000 cycles: hits are '
                                          'impulsive only and the slider is not driven (MODEL.md: '
                                          'ϖ beyond about 2); increase max_cycles to look further',
                               'status': 'not_driven',
                               'varpi': 2.0},
                              {'alpha': 0.5,
                               'beta': 1.0,
                               'kappa': 0.1,
                               'message': 'no contact recurred within 1000 cycles: hits are '
                                          'impulsive only and the slider is not driven (MODEL.md: '
                                          'ϖ beyond about 2); increase max_cycles to look further',
                               'status': 'not_driven',
                               'varpi': 2.0},
                              {'alpha': 1.0,
                               'beta': 1.0,
                               'kappa': 0.1,
                               'message': 'unbounded tangential motion: free-flight tangential '
                                          'resonance a·ϖ² = 1 with a = α = 1 at ϖ = 1 (α·ϖ² = 1; '
                                          'stick has a = α(1 + 1/β) = 2). Contact friction '
                                          'cancels at most the fraction ακ/2 = 0.05 < 1 of the '
                                          'resonant drive, so no periodic orbit exists: ζ at the '
                                          'section falls by ≥ π(1 − ακ/2) = 2.98451 per cycle '
                                          '(proven); measured 3.04151 per cycle over 256 cycles, '
                                          'amplitude 781.7 after 257 cycles. Move ϖ or α away '
                                          'from the resonance (α·ϖ² ≠ 1, e.g. by a few %)',
                               'status': 'unbounded',
                               'varpi': 1.0},
                              {'alpha': 1.0,
                               'beta': 1.0,
                               'kappa': 0.1,
                               'message': 'no contact recurred within 1000 cycles: hits are '
                                          'impulsive only and the slider is not driven (MODEL.md: '
                                          'ϖ beyond about 2); increase max_cycles to look further',
                               'status': 'not_driven',
                               'varpi': 2.0},
                              {'alpha': 1.5,
                               'beta': 1.0,
                               'kappa': 0.1,
                               'message': 'no contact recurred within 1000 cycles: hits are '
                                          'impulsive only and the slider is not driven (MODEL.md: '
                                          'ϖ beyond about 2); increase max_cycles to look further',
                               'status': 'not_driven',
                               'varpi': 2.0},
                              {'alpha': 2.0,
                               'beta': 1.0,
                               'kappa': 0.1,
                               'message': 'no contact recurred within 1000 cycles: hits are '
                                          'impulsive only and the slider is not driven (MODEL.md: '
                                          'ϖ beyond about 2); increase max_cycles to look further',
                               'status': 'not_driven',
                               'varpi': 2.0},
                              {'alpha': 2.5,
                               'beta': 1.0,
                               'kappa': 0.1,
                               'message': 'no contact recurred within 1000 cycles: hits are '
                                          'impulsive only and the slider is not driven (MODEL.md: '
                                          'ϖ beyond about 2); increase max_cycles to look further',
                               'status': 'not_driven',
                               'varpi': 2.0},
                              {'alpha': 3.0,
                               'beta': 1.0,
                               'kappa': 0.1,
                               'message': 'no contact recurred within 1000 cycles: hits are '
                                          'impulsive only and the slider is not driven (MODEL.md: '
                                          'ϖ beyond about 2); increase max_cycles to look further',
                               'status': 'not_driven',
                               'varpi': 2.0},
                              {'alpha': 3.5,
                               'beta': 1.0,
                               'kappa': 0.1,
                               'message': 'no contact recurred within 1000 cycles: hits are '
                                          'impulsive only and the slider is not driven (MODEL.md: '
                                          'ϖ beyond about 2); increase max_cycles to look further',
                               'status': 'not_driven',
                               'varpi': 2.0},
                              {'alpha': 4.0,
                               'beta': 1.0,
                               'kappa': 0.1,
                               'message': 'unbounded tangential motion: free-flight tangential '
                                          'resonance a·ϖ² = 1 with a = α = 4 at ϖ = 0.5 (α·ϖ² = '
                                          '1; stick has a = α(1 + 1/β) = 8). Contact friction '
                                          'cancels at most the fraction ακ/2 = 0.2 < 1 of the '
                                          'resonant drive, so no periodic orbit exists: ζ at the '
                                          'section falls by ≥ π(1 − ακ/2) = 2.51327 per cycle '
                                          '(proven); measured 2.52653 per cycle over 256 cycles, '
                                          'amplitude 649.5 after 257 cycles. Move ϖ or α away '
                                          'from the resonance (α·ϖ² ≠ 1, e.g. by a few %)',
                               'status': 'unbounded',
                               'varpi': 0.5},
                              {'alpha': 4.0,
                               'beta': 1.0,
                               'kappa': 0.1,
                               'message': 'no contact recurred within 1000 cycles: hits are '
                                          'impulsive only and the slider is not driven (MODEL.md: '
                                          'ϖ beyond about 2); increase max_cycles to look further',
                               'status': 'not_driven',
                               'varpi': 2.0},
                              {'alpha': 0.1,
                               'beta': 1.5,
                               'kappa': 0.1,
                               'message': 'no contact recurred within 1000 cycles: hits are '
                                          'impulsive only and the slider is not driven (MODEL.md: '
                                          'ϖ beyond about 2); increase max_cycles to look further',
                               'status': 'not_driven',
                               'varpi': 2.0},
                              {'alpha': 0.5,
                               'beta': 1.5,
                               'kappa': 0.1,
                               'message': 'no contact recurred within 1000 cycles: hits are '
                                          'impulsive only and the slider is not driven (MODEL.md: '
                                          'ϖ beyond about 2); increase max_cycles to look further',
                               'status': 'not_driven',
                               'varpi': 2.0},
                              {'alpha': 1.0,
                               'beta': 1.5,
                               'kappa': 0.1,
                               'message': 'unbounded tangential motion: free-flight tangential '
                                          'resonance a·ϖ² = 1 with a = α = 1 at ϖ = 1 (α·ϖ² = 1; '
                                          'stick has a = α(1 + 1/β) = 1.66667). Contact friction '
                                          'cancels at most the fraction ακ/2 = 0.05 < 1 of the '
                                          'resonant drive, so no periodic orbit exists: ζ at the '
                                          'section falls by ≥ π(1 − ακ/2) = 2.98451 per cycle '
                                          '(proven); measured 3.04153 per cycle over 256 cycles, '
                                          'amplitude 781.7 after 257 cycles. Move ϖ or α away '
                                          'from the resonance (α·ϖ² ≠ 1, e.g. by a few %)',
                               'status': 'unbounded',
                               'varpi': 1.0},
                              {'alpha': 1.0,
                               'beta': 1.5,
                               'kappa': 0.1,
                               'message': 'no contact recurred within 1000 cycles: hits are '
                                          'impulsive only and the slider is not driven (MODEL.md: '
                                          'ϖ beyond about 2); increase max_cycles to look further',
                               'status': 'not_driven',
                               'varpi': 2.0},
                              {'alpha': 1.5,
                               'beta': 1.5,
                               'kappa': 0.1,
                               'message': 'no contact recurred within 1000 cycles: hits are '
                                          'impulsive only and the slider is not driven (MODEL.md: '
                                          'ϖ beyond about 2); increase max_cycles to look further',
                               'status': 'not_driven',
                               'varpi': 2.0},
                              {'alpha': 2.0,
                               'beta': 1.5,
                               'kappa': 0.1,
                               'message': 'no contact recurred within 1000 cycles: hits are '
                                          'impulsive only and the slider is not driven (MODEL.md: '
                                          'ϖ beyond about 2); increase max_cycles to look further',
                               'status': 'not_driven',
                               'varpi': 2.0},
                              {'alpha': 2.5,
                               'beta': 1.5,
                               'kappa': 0.1,
                               'message': 'no contact recurred within 1000 cycles: hits are '
                                          'impulsive only and the slider is not driven (MODEL.md: '
                                          'ϖ beyond about 2); increase max_cycles to look further',
                               'status': 'not_driven',
                               'varpi': 2.0},
                              {'alpha': 3.0,
                               'beta': 1.5,
                               'kappa': 0.1,
                               'message': 'no contact recurred within 1000 cycles: hits are '
                                          'impulsive only and the slider is not driven (MODEL.md: '
                                          'ϖ beyond about 2); increase max_cycles to look further',
                               'status': 'not_driven',
                               'varpi': 2.0},
                              {'alpha': 3.5,
                               'beta': 1.5,
                               'kappa': 0.1,
                               'message': 'no contact recurred within 1000 cycles: hits are '
                                          'impulsive only and the slider is not driven (MODEL.md: '
                                          'ϖ beyond about 2); increase max_cycles to look further',
                               'status': 'not_driven',
                               'varpi': 2.0},
                              {'alpha': 4.0,
                               'beta': 1.5,
                               'kappa': 0.1,
                               'message': 'unbounded tangential motion: free-flight tangential '
                                          'resonance a·ϖ² = 1 with a = α = 4 at ϖ = 0.5 (α·ϖ² = '
                                          '1; stick has a = α(1 + 1/β) = 6.66667). Contact '
                                          'friction cancels at most the fraction ακ/2 = 0.2 < 1 '
                                          'of the resonant drive, so no periodic orbit exists: ζ '
                                          'at the section falls by ≥ π(1 − ακ/2) = 2.51327 per '
                                          'cycle (proven); measured 2.54752 per cycle over 256 '
                                          'cycles, amplitude 655 after 257 cycles. Move ϖ or α '
                                          'away from the resonance (α·ϖ² ≠ 1, e.g. by a few %)',
                               'status': 'unbounded',
                               'varpi': 0.5},
                              {'alpha': 4.0,
                               'beta': 1.5,
                               'kappa': 0.1,
                               'message': 'no contact recurred within 1000 cycles: hits are '
                                          'impulsive only and the slider is not driven (MODEL.md: '
                                          'ϖ beyond about 2); increase max_cycles to look further',
                               'status': 'not_driven',
                               'varpi': 2.0},
                              {'alpha': 0.1,
                               'beta': 0.1,
                               'kappa': 0.4,
                               'message': 'no contact recurred within 1000 cycles: hits are '
                                          'impulsive only and the slider is not driven (MODEL.md: '
                                          'ϖ beyond about 2); increase max_cycles to look further',
                               'status': 'not_driven',
                               'varpi': 2.0},
                              {'alpha': 0.5,
                               'beta': 0.1,
                               'kappa': 0.4,
                               'message': 'no contact recurred within 1000 cycles: hits are '
                                          'impulsive only and the slider is not driven (MODEL.md: '
                                          'ϖ beyond about 2); increase max_cycles to look further',
                               'status': 'not_driven',
                               'varpi': 2.0},
                              {'alpha': 1.0,
                               'beta': 0.1,
                               'kappa': 0.4,
                               'message': 'unbounded tangential motion: free-flight tangential '
                                          'resonance a·ϖ² = 1 with a = α = 1 at ϖ = 1 (α·ϖ² = 1; '
                                          'stick has a = α(1 + 1/β) = 11). Contact friction '
                                          'cancels at most the fraction ακ/2 = 0.2 < 1 of the '
                                          'resonant drive, so no periodic orbit exists: ζ at the '
                                          'section falls by ≥ π(1 − ακ/2) = 2.51327 per cycle '
                                          '(proven); measured 2.7414 per cycle over 256 cycles, '
                                          'amplitude 705.9 after 257 cycles. Move ϖ or α away '
                                          'from the resonance (α·ϖ² ≠ 1, e.g. by a few %)',
                               'status': 'unbounded',
                               'varpi': 1.0},
                              {'alpha': 1.0,
                               'beta': 0.1,
                               'kappa': 0.4,
                               'message': 'no contact recurred within 1000 cycles: hits are '
                                          'impulsive only and the slider is not driven (MODEL.md: '
                                          'ϖ beyond about 2); increase max_cycles to look further',
                               'status': 'not_driven',
                               'varpi': 2.0},
                              {'alpha': 1.5,
                               'beta': 0.1,
                               'kappa': 0.4,
                               'message': 'no contact recurred within 1000 cycles: hits are '
                                          'impulsive only and the slider is not driven (MODEL.md: '
                                          'ϖ beyond about 2); increase max_cycles to look further',
                               'status': 'not_driven',
                               'varpi': 2.0},
                              {'alpha': 2.0,
                               'beta': 0.1,
                               'kappa': 0.4,
                               'message': 'no contact recurred within 1000 cycles: hits are '
                                          'impulsive only and the slider is not driven (MODEL.md: '
                                          'ϖ beyond about 2); increase max_cycles to look further',
                               'status': 'not_driven',
                               'varpi': 2.0},
                              {'alpha': 2.5,
                               'beta': 0.1,
                               'kappa': 0.4,
                               'message': 'no contact recurred within 1000 cycles: hits are '
                                          'impulsive only and the slider is not driven (MODEL.md: '
                                          'ϖ beyond about 2); increase max_cycles to look further',
                               'status': 'not_driven',
                               'varpi': 2.0},
                              {'alpha': 3.0,
                               'beta': 0.1,
                               'kappa': 0.4,
                               'message': 'no contact recurred within 1000 cycles: hits are '
                                          'impulsive only and the slider is not driven (MODEL.md: '
                                          'ϖ beyond about 2); increase max_cycles to look further',
                               'status': 'not_driven',
                               'varpi': 2.0},
                              {'alpha': 3.5,
                               'beta': 0.1,
                               'kappa': 0.4,
                               'message': 'no contact recurred within 1000 cycles: hits are '
                                          'impulsive only and the slider is not driven (MODEL.md: '
                                          'ϖ beyond about 2); increase max_cycles to look further',
                               'status': 'not_driven',
                               'varpi': 2.0},
                              {'alpha': 4.0,
                               'beta': 0.1,
                               'kappa': 0.4,
                               'message': 'unbounded tangential motion: free-flight tangential '
                                          'resonance a·ϖ² = 1 with a = α = 4 at ϖ = 0.5 (α·ϖ² = '
                                          '1; stick has a = α(1 + 1/β) = 44). Contact friction '
                                          'cancels at most the fraction ακ/2 = 0.8 < 1 of the '
                                          'resonant drive, so no periodic orbit exists: ζ at the '
                                          'section falls by ≥ π(1 − ακ/2) = 0.628319 per cycle '
                                          '(proven); measured 0.740088 per cycle over 256 cycles, '
                                          'amplitude 191.3 after 257 cycles. Move ϖ or α away '
                                          'from the resonance (α·ϖ² ≠ 1, e.g. by a few %)',
                               'status': 'unbounded',
                               'varpi': 0.5},
                              {'alpha': 4.0,
                               'beta': 0.1,
                               'kappa': 0.4,
                               'message': 'no contact recurred within 1000 cycles: hits are '
                                          'impulsive only and the slider is not driven (MODEL.md: '
                                          'ϖ beyond about 2); increase max_cycles to look further',
                               'status': 'not_driven',
                               'varpi': 2.0},
                              {'alpha': 0.1,
                               'beta': 0.5,
                               'kappa': 0.4,
                               'message': 'no contact recurred within 1000 cycles: hits are '
                                          'impulsive only and the slider is not driven (MODEL.md: '
                                          'ϖ beyond about 2); increase max_cycles to look further',
                               'status': 'not_driven',
                               'varpi': 2.0},
                              {'alpha': 0.5,
                               'beta': 0.5,
                               'kappa': 0.4,
                               'message': 'no contact recurred within 1000 cycles: hits are '
                                          'impulsive only and the slider is not driven (MODEL.md: '
                                          'ϖ beyond about 2); increase max_cycles to look further',
                               'status': 'not_driven',
                               'varpi': 2.0},
                              {'alpha': 1.0,
                               'beta': 0.5,
                               'kappa': 0.4,
                               'message': 'unbounded tangential motion: free-flight tangential '
                                          'resonance a·ϖ² = 1 with a = α = 1 at ϖ = 1 (α·ϖ² = 1; '
                                          'stick has a = α(1 + 1/β) = 3). Contact friction '
                                          'cancels at most the fraction ακ/2 = 0.2 < 1 of the '
                                          'resonant drive, so no periodic orbit exists: ζ at the '
                                          'section falls by ≥ π(1 − ακ/2) = 2.51327 per cycle '
                                          '(proven); measured 2.7422 per cycle over 256 cycles, '
                                          'amplitude 706.1 after 257 cycles. Move ϖ or α away '
                                          'from the resonance (α·ϖ² ≠ 1, e.g. by a few %)',
                               'status': 'unbounded',
                               'varpi': 1.0},
                              {'alpha': 1.0,
                               'beta': 0.5,
                               'kappa': 0.4,
                               'message': 'no contact recurred within 1000 cycles: hits are '
                                          'impulsive only and the slider is not driven (MODEL.md: '
                                          'ϖ beyond about 2); increase max_cycles to look further',
                               'status': 'not_driven',
                               'varpi': 2.0},
                              {'alpha': 1.5,
                               'beta': 0.5,
                               'kappa': 0.4,
                               'message': 'no contact recurred within 1000 cycles: hits are '
                                          'impulsive only and the slider is not driven (MODEL.md: '
                                          'ϖ beyond about 2); increase max_cycles to look further',
                               'status': 'not_driven',
                               'varpi': 2.0},
                              {'alpha': 2.0,
                               'beta': 0.5,
                               'kappa': 0.4,
                               'message': 'no contact recurred within 1000 cycles: hits are '
                                          'impulsive only and the slider is not driven (MODEL.md: '
                                          'ϖ beyond about 2); increase max_cycles to look further',
                               'status': 'not_driven',
                               'varpi': 2.0},
                              {'alpha': 2.5,
                               'beta': 0.5,
                               'kappa': 0.4,
                               'message': 'no contact recurred within 1000 cycles: hits are '
                                          'impulsive only and the slider is not driven (MODEL.md: '
                                          'ϖ beyond about 2); increase max_cycles to look further',
                               'status': 'not_driven',
                               'varpi': 2.0},
                              {'alpha': 3.0,
                               'beta': 0.5,
                               'kappa': 0.4,
                               'message': 'no contact recurred within 1000 cycles: hits are '
                                          'impulsive only and the slider is not driven (MODEL.md: '
                                          'ϖ beyond about 2); increase max_cycles to look further',
                               'status': 'not_driven',
                               'varpi': 2.0},
                              {'alpha': 3.5,
                               'beta': 0.5,
                               'kappa': 0.4,
                               'message': 'no contact recurred within 1000 cycles: hits are '
                                          'impulsive only and the slider is not driven (MODEL.md: '
                                          'ϖ beyond about 2); increase max_cycles to look further',
                               'status': 'not_driven',
                               'varpi': 2.0},
                              {'alpha': 4.0,
                               'beta': 0.5,
                               'kappa': 0.4,
                               'message': 'unbounded tangential motion: free-flight tangential '
                                          'resonance a·ϖ² = 1 with a = α = 4 at ϖ = 0.5 (α·ϖ² = '
                                          '1; stick has a = α(1 + 1/β) = 12). Contact friction '
                                          'cancels at most the fraction ακ/2 = 0.8 < 1 of the '
                                          'resonant drive, so no periodic orbit exists: ζ at the '
                                          'section falls by ≥ π(1 − ακ/2) = 0.628319 per cycle '
                                          '(proven); measured 1.29883 per cycle over 256 cycles, '
                                          'amplitude 334.9 after 257 cycles. Move ϖ or α away '
                                          'from the resonance (α·ϖ² ≠ 1, e.g. by a few %)',
                               'status': 'unbounded',
                               'varpi': 0.5},
                              {'alpha': 4.0,
                               'beta': 0.5,
                               'kappa': 0.4,
                               'message': 'no contact recurred within 1000 cycles: hits are '
                                          'impulsive only and the slider is not driven (MODEL.md: '
                                          'ϖ beyond about 2); increase max_cycles to look further',
                               'status': 'not_driven',
                               'varpi': 2.0},
                              {'alpha': 0.1,
                               'beta': 1.0,
                               'kappa': 0.4,
                               'message': 'no contact recurred within 1000 cycles: hits are '
                                          'impulsive only and the slider is not driven (MODEL.md: '
                                          'ϖ beyond about 2); increase max_cycles to look further',
                               'status': 'not_driven',
                               'varpi': 2.0},
                              {'alpha': 0.5,
                               'beta': 1.0,
                               'kappa': 0.4,
                               'message': 'no contact recurred within 1000 cycles: hits are '
                                          'impulsive only and the slider is not driven (MODEL.md: '
                                          'ϖ beyond about 2); increase max_cycles to look further',
                               'status': 'not_driven',
                               'varpi': 2.0},
                              {'alpha': 1.0,
                               'beta': 1.0,
                               'kappa': 0.4,
                               'message': 'unbounded tangential motion: free-flight tangential '
                                          'resonance a·ϖ² = 1 with a = α = 1 at ϖ = 1 (α·ϖ² = 1; '
                                          'stick has a = α(1 + 1/β) = 2). Contact friction '
                                          'cancels at most the fraction ακ/2 = 0.2 < 1 of the '
                                          'resonant drive, so no periodic orbit exists: ζ at the '
                                          'section falls by ≥ π(1 − ακ/2) = 2.51327 per cycle '
                                          '(proven); measured 2.74453 per cycle over 256 cycles, '
                                          'amplitude 706.6 after 257 cycles. Move ϖ or α away '
                                          'from the resonance (α·ϖ² ≠ 1, e.g. by a few %)',
                               'status': 'unbounded',
                               'varpi': 1.0},
                              {'alpha': 1.0,
                               'beta': 1.0,
                               'kappa': 0.4,
                               'message': 'no contact recurred within 1000 cycles: hits are '
                                          'impulsive only and the slider is not driven (MODEL.md: '
                                          'ϖ beyond about 2); increase max_cycles to look further',
                               'status': 'not_driven',
                               'varpi': 2.0},
                              {'alpha': 1.5,
                               'beta': 1.0,
                               'kappa': 0.4,
                               'message': 'no contact recurred within 1000 cycles: hits are '
                                          'impulsive only and the slider is not driven (MODEL.md: '
                                          'ϖ beyond about 2); increase max_cycles to look further',
                               'status': 'not_driven',
                               'varpi': 2.0},
                              {'alpha': 2.0,
                               'beta': 1.0,
                               'kappa': 0.4,
                               'message': 'no contact recurred within 1000 cycles: hits are '
                                          'impulsive only and the slider is not driven (MODEL.md: '
                                          'ϖ beyond about 2); increase max_cycles to look further',
                               'status': 'not_driven',
                               'varpi': 2.0},
                              {'alpha': 2.5,
                               'beta': 1.0,
                               'kappa': 0.4,
                               'message': 'no contact recurred within 1000 cycles: hits are '
                                          'impulsive only and the slider is not driven (MODEL.md: '
                                          'ϖ beyond about 2); increase max_cycles to look further',
                               'status': 'not_driven',
                               'varpi': 2.0},
                              {'alpha': 3.0,
                               'beta': 1.0,
                               'kappa': 0.4,
                               'message': 'no contact recurred within 1000 cycles: hits are '
                                          'impulsive only and the slider is not driven (MODEL.md: '
                                          'ϖ beyond about 2); increase max_cycles to look further',
                               'status': 'not_driven',
                               'varpi': 2.0},
                              {'alpha': 3.5,
                               'beta': 1.0,
                               'kappa': 0.4,
                               'message': 'no contact recurred within 1000 cycles: hits are '
                                          'impulsive only and the slider is not driven (MODEL.md: '
                                          'ϖ beyond about 2); increase max_cycles to look further',
                               'status': 'not_driven',
                               'varpi': 2.0},
                              {'alpha': 4.0,
                               'beta': 1.0,
                               'kappa': 0.4,
                               'message': 'unbounded tangential motion: free-flight tangential '
                                          'resonance a·ϖ² = 1 with a = α = 4 at ϖ = 0.5 (α·ϖ² = '
                                          '1; stick has a = α(1 + 1/β) = 8). Contact friction '
                                          'cancels at most the fraction ακ/2 = 0.8 < 1 of the '
                                          'resonant drive, so no periodic orbit exists: ζ at the '
                                          'section falls by ≥ π(1 − ακ/2) = 0.628319 per cycle '
                                          '(proven); measured 1.63707 per cycle over 256 cycles, '
                                          'amplitude 421.8 after 257 cycles. Move ϖ or α away '
                                          'from the resonance (α·ϖ² ≠ 1, e.g. by a few %)',
                               'status': 'unbounded',
                               'varpi': 0.5},
                              {'alpha': 4.0,
                               'beta': 1.0,
                               'kappa': 0.4,
                               'message': 'no contact recurred within 1000 cycles: hits are '
                                          'impulsive only and the slider is not driven (MODEL.md: '
                                          'ϖ beyond about 2); increase max_cycles to look further',
                               'status': 'not_driven',
                               'varpi': 2.0},
                              {'alpha': 0.1,
                               'beta': 1.5,
                               'kappa': 0.4,
                               'message': 'no contact recurred within 1000 cycles: hits are '
                                          'impulsive only and the slider is not driven (MODEL.md: '
                                          'ϖ beyond about 2); increase max_cycles to look further',
                               'status': 'not_driven',
                               'varpi': 2.0},
                              {'alpha': 0.5,
                               'beta': 1.5,
                               'kappa': 0.4,
                               'message': 'no contact recurred within 1000 cycles: hits are '
                                          'impulsive only and the slider is not driven (MODEL.md: '
                                          'ϖ beyond about 2); increase max_cycles to look further',
                               'status': 'not_driven',
                               'varpi': 2.0},
                              {'alpha': 1.0,
                               'beta': 1.5,
                               'kappa': 0.4,
                               'message': 'unbounded tangential motion: free-flight tangential '
                                          'resonance a·ϖ² = 1 with a = α = 1 at ϖ = 1 (α·ϖ² = 1; '
                                          'stick has a = α(1 + 1/β) = 1.66667). Contact friction '
                                          'cancels at most the fraction ακ/2 = 0.2 < 1 of the '
                                          'resonant drive, so no periodic orbit exists: ζ at the '
                                          'section falls by ≥ π(1 − ακ/2) = 2.51327 per cycle '
                                          '(proven); measured 2.74861 per cycle over 256 cycles, '
                                          'amplitude 707.5 after 257 cycles. Move ϖ or α away '
                                          'from the resonance (α·ϖ² ≠ 1, e.g. by a few %)',
                               'status': 'unbounded',
                               'varpi': 1.0},
                              {'alpha': 1.0,
                               'beta': 1.5,
                               'kappa': 0.4,
                               'message': 'no contact recurred within 1000 cycles: hits are '
                                          'impulsive only and the slider is not driven (MODEL.md: '
                                          'ϖ beyond about 2); increase max_cycles to look further',
                               'status': 'not_driven',
                               'varpi': 2.0},
                              {'alpha': 1.5,
                               'beta': 1.5,
                               'kappa': 0.4,
                               'message': 'no contact recurred within 1000 cycles: hits are '
                                          'impulsive only and the slider is not driven (MODEL.md: '
                                          'ϖ beyond about 2); increase max_cycles to look further',
                               'status': 'not_driven',
                               'varpi': 2.0},
                              {'alpha': 2.0,
                               'beta': 1.5,
                               'kappa': 0.4,
                               'message': 'no contact recurred within 1000 cycles: hits are '
                                          'impulsive only and the slider is not driven (MODEL.md: '
                                          'ϖ beyond about 2); increase max_cycles to look further',
                               'status': 'not_driven',
                               'varpi': 2.0},
                              {'alpha': 2.5,
                               'beta': 1.5,
                               'kappa': 0.4,
                               'message': 'no contact recurred within 1000 cycles: hits are '
                                          'impulsive only and the slider is not driven (MODEL.md: '
                                          'ϖ beyond about 2); increase max_cycles to look further',
                               'status': 'not_driven',
                               'varpi': 2.0},
                              {'alpha': 3.0,
                               'beta': 1.5,
                               'kappa': 0.4,
                               'message': 'no contact recurred within 1000 cycles: hits are '
                                          'impulsive only and the slider is not driven (MODEL.md: '
                                          'ϖ beyond about 2); increase max_cycles to look further',
                               'status': 'not_driven',
                               'varpi': 2.0},
                              {'alpha': 3.5,
                               'beta': 1.5,
                               'kappa': 0.4,
                               'message': 'no contact recurred within 1000 cycles: hits are '
                                          'impulsive only and the slider is not driven (MODEL.md: '
                                          'ϖ beyond about 2); increase max_cycles to look further',
                               'status': 'not_driven',
                               'varpi': 2.0},
                              {'alpha': 4.0,
                               'beta': 1.5,
                               'kappa': 0.4,
                               'message': 'unbounded tangential motion: free-flight tangential '
                                          'resonance a·ϖ² = 1 with a = α = 4 at ϖ = 0.5 (α·ϖ² = '
                                          '1; stick has a = α(1 + 1/β) = 6.66667). Contact '
                                          'friction cancels at most the fraction ακ/2 = 0.8 < 1 '
                                          'of the resonant drive, so no periodic orbit exists: ζ '
                                          'at the section falls by ≥ π(1 − ακ/2) = 0.628319 per '
                                          'cycle (proven); measured 1.83123 per cycle over 256 '
                                          'cycles, amplitude 471.6 after 257 cycles. Move ϖ or α '
                                          'away from the resonance (α·ϖ² ≠ 1, e.g. by a few %)',
                               'status': 'unbounded',
                               'varpi': 0.5},
                              {'alpha': 4.0,
                               'beta': 1.5,
                               'kappa': 0.4,
                               'message': 'no contact recurred within 1000 cycles: hits are '
                                          'impulsive only and the slider is not driven (MODEL.md: '
                                          'ϖ beyond about 2); increase max_cycles to look further',
                               'status': 'not_driven',
                               'varpi': 2.0}],
            'points': 1152,
            'rate': 0.022556390977443608,
            'rigid_mode_disagreement': 0.7161654135338346,
            'safety': 1.25,
            'sample': {'converged': 1500,
                       'mispredicted': 27,
                       'mispredictions': [{'alpha': 0.16118366649017385,
                                           'beta': 0.13477618681405326,
                                           'delta_s': 0.5366356836732857,
                                           'kappa': 0.25115353132381324,
                                           'lam': 18.168169934426565,
                                           'mode': 'push',
                                           'varpi': 0.5812257140659223},
                                          {'alpha': 0.5877711890325636,
                                           'beta': 0.27589380914419714,
                                           'delta_s': 0.9119829706129563,
                                           'kappa': 0.28556013342689057,
                                           'lam': 4.948569627211767,
                                           'mode': 'push',
                                           'varpi': 0.5804932371429294},
                                          {'alpha': 0.6299197859732475,
                                           'beta': 0.24767334451929596,
                                           'delta_s': 0.6287805723106659,
                                           'kappa': 0.12008064888150832,
                                           'lam': 4.9052737783792,
                                           'mode': 'push',
                                           'varpi': 0.5655678765644748},
                                          {'alpha': 0.5051103128490521,
                                           'beta': 1.1292757526933843,
                                           'delta_s': 0.13239553457331765,
                                           'kappa': 0.3167436554735289,
                                           'lam': 4.609311646689211,
                                           'mode': 'push',
                                           'varpi': 0.6558144466148983},
                                          {'alpha': 0.7840672640326747,
                                           'beta': 0.7549463191339677,
                                           'delta_s': 2.1996312245847363,
                                           'kappa': 0.16567124157450785,
                                           'lam': 4.534311048811013,
                                           'mode': 'push',
                                           'varpi': 0.5295905361117427},
                                          {'alpha': 0.3676197931015325,
                                           'beta': 1.2017450205568683,
                                           'delta_s': 0.09217386041429423,
                                           'kappa': 0.32578686142329827,
                                           'lam': 4.430242332915922,
                                           'mode': 'push',
                                           'varpi': 0.7841806755670717},
                                          {'alpha': 0.6194797276840794,
                                           'beta': 1.0835522689160995,
                                           'delta_s': 2.9532738349436145,
                                           'kappa': 0.22636115293185557,
                                           'lam': 4.370753060660767,
                                           'mode': 'push',
                                           'varpi': 0.6079803788585403},
                                          {'alpha': 0.5358529035790884,
                                           'beta': 0.39818339739667064,
                                           'delta_s': 3.464966082797027,
                                           'kappa': 0.2876785575021815,
                                           'lam': 4.352869636374664,
                                           'mode': 'push',
                                           'varpi': 0.6509953483169816},
                                          {'alpha': 0.3019738240616455,
                                           'beta': 0.5216883725310207,
                                           'delta_s': 0.7581840594766915,
                                           'kappa': 0.2285388441348986,
                                           'lam': 4.243462981895128,
                                           'mode': 'push',
                                           'varpi': 0.8818205068030487},
                                          {'alpha': 2.8780427415518837,
                                           'beta': 0.6478757275457354,
                                           'delta_s': 1.839544289521728,
                                           'kappa': 0.2317479494234698,
                                           'lam': 1.1798958530297634,
                                           'mode': 'push',
                                           'varpi': 0.5366475151492747},
                                          {'alpha': 2.075780506387838,
                                           'beta': 0.5261211584512512,
                                           'delta_s': 0.1858339865841278,
                                           'kappa': 0.2757417177763868,
                                           'lam': 1.1742999115567954,
                                           'mode': 'push',
                                           'varpi': 0.6314595550486378},
                                          {'alpha': 2.8117317727673807,
                                           'beta': 0.2188895492788638,
                                           'delta_s': 1.1797865395263396,
                                           'kappa': 0.10071598353458583,
                                           'lam': 1.1645080305981532,
                                           'mode': 'push',
                                           'varpi': 0.5384007014024349},
                                          {'alpha': 3.201311586716587,
                                           'beta': 0.2944699083804483,
                                           'delta_s': 1.9060848821559904,
                                           'kappa': 0.1326411505637777,
                                           'lam': 1.155999888014975,
                                           'mode': 'push',
                                           'varpi': 0.5059017194526813},
                                          {'alpha': 2.2007471157392127,
                                           'beta': 1.2703506689153314,
                                           'delta_s': 2.268823064440218,
                                           'kappa': 0.34803337421939096,
                                           'lam': 1.1290018620246323,
                                           'mode': 'push',
                                           'varpi': 0.638352433030569},
                                          {'alpha': 2.302413458715926,
                                           'beta': 0.605264685477696,
                                           'delta_s': 2.5711738774549326,
                                           'kappa': 0.28267235965363835,
                                           'lam': 1.1268318391644356,
                                           'mode': 'push',
                                           'varpi': 0.6132976919611005},
                                          {'alpha': 2.2760821250105443,
                                           'beta': 0.9988482795260356,
                                           'delta_s': 4.312194142740723,
                                           'kappa': 0.34655972833874665,
                                           'lam': 1.1130073653849601,
                                           'mode': 'push',
                                           'varpi': 0.6282661921786831},
                                          {'alpha': 2.735486624662874,
                                           'beta': 0.5780446776349006,
                                           'delta_s': 8.533213948311758,
                                           'kappa': 0.3269101021480807,
                                           'lam': 1.0828796884091738,
                                           'mode': 'push',
                                           'varpi': 0.5706784994187002},
                                          {'alpha': 2.4518952577396727,
                                           'beta': 1.4150259380751709,
                                           'delta_s': 18.836239704625363,
                                           'kappa': 0.31233198772693704,
                                           'lam': 1.0651747786179948,
                                           'mode': 'push',
                                           'varpi': 0.6245691859423012},
                                          {'alpha': 1.7642323094790038,
                                           'beta': 0.17695843910811934,
                                           'delta_s': -1363.4388468415461,
                                           'kappa': 0.1414052553501959,
                                           'lam': 0.9459284486712912,
                                           'mode': 'pull',
                                           'varpi': 0.7527493664277236},
                                          {'alpha': 3.6210030627427945,
                                           'beta': 0.701739623029631,
                                           'delta_s': 22.66487033296165,
                                           'kappa': 0.3319404636936726,
                                           'lam': 1.0484957863140891,
                                           'mode': 'push',
                                           'varpi': 0.5055478810854312},
                                          {'alpha': 3.180851325871123,
                                           'beta': 1.3280286083222184,
                                           'delta_s': 72.02838325551215,
                                           'kappa': 0.3380780693860058,
                                           'lam': 1.0470054612324344,
                                           'mode': 'push',
                                           'varpi': 0.5536917400117783},
                                          {'alpha': 3.6518233786450622,
                                           'beta': 1.2942145950144592,
                                           'delta_s': 61.17304076220284,
                                           'kappa': 0.24360763402698116,
                                           'lam': 1.0431333616272527,
                                           'mode': 'push',
                                           'varpi': 0.5166861354604421},
                                          {'alpha': 3.7635116086589155,
                                           'beta': 1.3164920179377555,
                                           'delta_s': 82.79333839971821,
                                           'kappa': 0.24654136979501748,
                                           'lam': 1.0396202033911297,
                                           'mode': 'push',
                                           'varpi': 0.5102928147609058},
                                          {'alpha': 3.502842101213045,
                                           'beta': 1.3344971279167117,
                                           'delta_s': 147.08136801981857,
                                           'kappa': 0.27970862342855995,
                                           'lam': 1.0330540531359653,
                                           'mode': 'push',
                                           'varpi': 0.5310137134114746},
                                          {'alpha': 2.392107505777883,
                                           'beta': 0.24273520030748108,
                                           'delta_s': 6.494798372167863,
                                           'kappa': 0.2710434046439512,
                                           'lam': 1.013796031878604,
                                           'mode': 'push',
                                           'varpi': 0.6126047769820331},
                                          {'alpha': 2.6209895155485508,
                                           'beta': 0.4509881397135874,
                                           'delta_s': 12.629410082406157,
                                           'kappa': 0.12634790171298915,
                                           'lam': 1.0075434968380523,
                                           'mode': 'push',
                                           'varpi': 0.6080622659913694},
                                          {'alpha': 2.843022176684721,
                                           'beta': 0.877005273284534,
                                           'delta_s': 87.28138574646324,
                                           'kappa': 0.25449773824140687,
                                           'lam': 1.0068572465209842,
                                           'mode': 'push',
                                           'varpi': 0.589009318993575}],
                       'points': 1500,
                       'rate': 0.018},
            'trust_margin': 38.836363636363636,
            'trust_margin_by_beta': {'0.1': 38.836363636363636,
                                     '0.5': 0.11806375442739081,
                                     '1.0': 0.1428571428571428,
                                     '1.5': 0.18614718614718617},
            'trust_table': [[48.54545454545455,
                             4.19108704546833,
                             4.511639558361513,
                             0.23268398268398272],
                            [3.747680890538034,
                             4.05432872736891,
                             4.287802916144903,
                             0.05311865005742572],
                            [0.0, 0.0, 0.0, 0.0],
                            [0.05648688046647199, 0.0, 0.0, 0.0],
                            [0.0, 0.0, 0.0, 0.0]],
            'varpi_bins': [0.5, 0.7, 0.9, 1.2, 1.6, 2.0]},
 'rigid': {'coef': 20.816526796789084,
           'power': 0.7699510167993905,
           'samples': [{'alpha': 0.1,
                        'beta': 0.9,
                        'error': 0.12883146513055532,
                        'kappa': 0.4,
                        'varpi': 0.9},
                       {'alpha': 0.03,
                        'beta': 0.9,
                        'error': 0.08937961576795093,
                        'kappa': 0.4,
                        'varpi': 0.9},
                       {'alpha': 0.01,
                        'beta': 0.9,
                        'error': 0.2615276175152499,
                        'kappa': 0.4,
                        'varpi': 0.9},
                       {'alpha': 0.003,
                        'beta': 0.9,
                        'error': 0.03550800304580936,
                        'kappa': 0.4,
                        'varpi': 0.9},
                       {'alpha': 0.001,
                        'beta': 0.9,
                        'error': 0.02735533691093993,
                        'kappa': 0.4,
                        'varpi': 0.9},
                       {'alpha': 0.0003,
                        'beta': 0.9,
                        'error': 0.04036121188793541,
                        'kappa': 0.4,
                        'varpi': 0.9},
                       {'alpha': 0.0001,
                        'beta': 0.9,
                        'error': 0.010733900797221444,
                        'kappa': 0.4,
                        'varpi': 0.9},
                       {'alpha': 0.1,
                        'beta': 0.5,
                        'error': 0.22438396303739003,
                        'kappa': 0.1,
                        'varpi': 1.5},
                       {'alpha': 0.03,
                        'beta': 0.5,
                        'error': 0.07965167274901,
                        'kappa': 0.1,
                        'varpi': 1.5},
                       {'alpha': 0.01,
                        'beta': 0.5,
                        'error': 0.028523837820442467,
                        'kappa': 0.1,
                        'varpi': 1.5},
                       {'alpha': 0.003,
                        'beta': 0.5,
                        'error': 0.00037144700454216814,
                        'kappa': 0.1,
                        'varpi': 1.5},
                       {'alpha': 0.001,
                        'beta': 0.5,
                        'error': 0.002093283732770091,
                        'kappa': 0.1,
                        'varpi': 1.5},
                       {'alpha': 0.0003,
                        'beta': 0.5,
                        'error': 0.0006140283449589139,
                        'kappa': 0.1,
                        'varpi': 1.5},
                       {'alpha': 0.0001,
                        'beta': 0.5,
                        'error': 0.00039774761029480433,
                        'kappa': 0.1,
                        'varpi': 1.5},
                       {'alpha': 0.1,
                        'beta': 1.5,
                        'error': 0.26843551708662255,
                        'kappa': 0.4,
                        'varpi': 0.6},
                       {'alpha': 0.03,
                        'beta': 1.5,
                        'error': 0.07742491199215912,
                        'kappa': 0.4,
                        'varpi': 0.6},
                       {'alpha': 0.01,
                        'beta': 1.5,
                        'error': 0.015703914009804053,
                        'kappa': 0.4,
                        'varpi': 0.6},
                       {'alpha': 0.003,
                        'beta': 1.5,
                        'error': 0.005114552515942661,
                        'kappa': 0.4,
                        'varpi': 0.6},
                       {'alpha': 0.001,
                        'beta': 1.5,
                        'error': 0.001698758811309355,
                        'kappa': 0.4,
                        'varpi': 0.6},
                       {'alpha': 0.0003,
                        'beta': 1.5,
                        'error': 0.0008999075582586537,
                        'kappa': 0.4,
                        'varpi': 0.6},
                       {'alpha': 0.0001,
                        'beta': 1.5,
                        'error': 0.00028073250040982464,
                        'kappa': 0.4,
                        'varpi': 0.6}]}}
