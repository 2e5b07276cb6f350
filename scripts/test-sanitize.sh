#!/usr/bin/env bash
# The native GoogleTest suites (core, glare, optimizer, photometry; Vulkan on lavapipe where the
# backend is built) compiled with AddressSanitizer (leak check on), UndefinedBehaviorSanitizer and
# -D_GLIBCXX_ASSERTIONS into build-asan/, then run through CTest. A finding aborts the test that
# made it. scripts/test.sh runs this after the main suite; docs/testing.md "Sanitizer build".
# Extra arguments go to the CMake configure step. LIGHTSOLVER_SANITIZE_STEPS=build or =test runs
# one half (scripts/test.sh builds beside the main CTest run, then tests); default both.
set -euo pipefail
cd "$(dirname "$0")/.."
root=$PWD
dir=build-asan
jobs=$(nproc 2>/dev/null || echo 2)

# The first finding ends the test with a stack. Leak suppressions are for memory that libraries
# outside this project keep (Tests/sanitizers/lsan.supp says which and why).
export ASAN_OPTIONS="detect_leaks=1:check_initialization_order=1:strict_string_checks=1:abort_on_error=1"
export UBSAN_OPTIONS="print_stacktrace=1:halt_on_error=1"
export LSAN_OPTIONS="suppressions=$root/Tests/sanitizers/lsan.supp:print_suppressions=0"

# (CMake's regular expressions allow at most ten groups: list further names without one.)
# Statistical tests that repeat a run over hundreds of seeds or trace 10^7 photons take minutes
# each under ASan; the code they run is run by the shorter tests of the same suites (they check
# coverage rates and counts at scale, which the main CTest run checks).
slow='^(CiHonesty\.|Decide\.StoppingAtTheFirstDecidedLook|ObserverAgainstTable\.StandardRoom'
slow+='|ObserverGridCoverage\.|IntervalCoverage\..*Over500Seeds|DaylightFactorCoverage\.'
slow+='|Backends/HardCases\.(EveryPhotonCountedPastFloatResolution|TinyTargetInAHugeHall)'
# The sky's and the glazing's emission run under the sanitizers in their shorter traced tests
# (the 1 cm² skylight, the roof openings); these two trace 10^7 photons through a whole room,
# and the fifteen CIE skies are fifteen runs of the clear-sky case that does run under them.
slow+='|Backends/SkyTraced\.(SideLitRoomPortalAndNoPortalAgree'
slow+='|FifteenCieSkiesUnobstructedHorizontalIlluminance)'
slow+='|Backends/GlazingTraced\.VerticalWindowUnderTheOvercastSky'
# A year of coefficients through an open probe (2·10⁷ photons, 4414 hours) and the patches'
# fluxes of five skies (1162 sky tables): the same code runs in the three-hour room and the
# uniform skylight under the sanitizers.
slow+='|dc\.DaylightCoefficients\.OpenProbeReadsTheSkyAndSunEveryHour|SkyPatch\.PatchFluxesAddUp'
# A hundred searches of the same scene (a rate), the other ReusedTraces tests run its code.
slow+='|optimizer\.ReusedTraces\.ReportedMembersStayFeasibleOver100Seeds'
# Every sample file traced through Embree: one .ies and one .ldt stay (and every file through
# Vulkan); the photometry suite parses and samples all eight sample files under the sanitizers.
slow+='|SampleFiles/Photometric\.IlluminanceFollowsTheCandelaTableInManyDirections/'
slow+='embree_(downlight_ies|downlight_ldt|wallwasher_ies|wallwasher_ldt)( |$)'
# On Vulkan the sanitizers see only the host side (the shaders run in lavapipe, uninstrumented):
# the sky's upload with and without portals runs in the 1 cm² skylight and SkyObstructed's
# entries, a reflective cube's in Cie171CubeWithCentralSource; these three trace 10^6-10^7
# photons for the shader's numbers, which the main run checks.
slow+='|Backends/SkyTraced\.(RoofOpeningInABlackRoomGivesLPiTimesTheConfigurationFactor'
slow+='|UnobstructedHorizontalIlluminanceWithoutPortals)/"vulkan"'
slow+='|Backends/Stability\.ReflectiveCubeFarFromOriginMatchesCie171/"vulkan"'
# The same for glass on Vulkan (8-10 s each under ASan): its host side (glass materials, the sun
# and sky beside a lamp) runs in GlazingTraced.TransmittanceOfOnePercent and the clear pane.
slow+='|Backends/GlazingTraced\.SunAndSkyBesideALampTenToTheFiveTimesDimmerEachResolved/"vulkan"'
slow+='|Backends/GlazingTraced\.GlazedRoofOpeningUnderTheUniformSky/"vulkan"'
slow+='|Backends/HardCases\.SolidGlassSphereAroundALampConservesEnergy/"vulkan"'
slow+='|Backends/ClosedForm\.AbsorbingGlassSlabAndThinPaneAgree/vulkan'
slow+='|Backends/ClosedForm\.MirrorAddsTheImageSource/vulkan'
# Next-event estimation: the 200-seed coverage and the photometric files against their photons
# repeat runs whose code the other NextEvent entries run under the sanitizers; the closed forms
# with it on Vulkan (its shadow rays run in lavapipe) repeat the Embree ones' host code.
slow+='|Backends/NextEvent\.(PerCellCoverageOver200Seeds|PhotometricFilesAgreeWithTheirPhotons)'
# Connected reflected light: the 200-seed coverage repeats what its closed-form entries run.
slow+='|ReflectionConnection\.PerCellCoverageOver200Seeds'
# A glass slab (shadow rays blocked: no direct part) and a mirror (its image comes by photons)
# with next-event estimation on trace what their plain Embree entries trace; the direct parts'
# host code runs in the other embree_nee entries.
slow+='|Backends/ClosedForm\.AbsorbingGlassSlabAndThinPaneAgree/embree_nee'
slow+='|Backends/ClosedForm\.MirrorAddsTheImageSource/embree_nee'
slow+='|Backends/(ClosedForm|IndependentChecks)\..*/vulkan_nee'
# Issue 28, fourth round: coverage loops over seeds (QuasiRandomNextEvent.* and Qmc.* run the same
# code once), a Vulkan year beside its Embree twin, a Perez sweep, whole-sky totals, two sky
# openings beside the roof opening that stays, two of the four optimizer scene examples (the
# constrained search has its own unit tests), the lamps a million apart on Embree (Vulkan's
# stays), and the glazed sun and sky beside a lamp (TransmittanceOfOnePercent runs glazing).
slow+='|QuasiRandomCoverage\.|NextEvent/QuasiRandomCoverageNee\.'
slow+='|dc\.Backends/DaylightCoefficientsTraced\.HoursEqualPointInTimeRuns/"vulkan"'
slow+='|SkyModels\.PerezIsPositiveNormalisedAndContinuousInEachBin'
slow+='|sky_patches\.SkyMatrix\.RadianceSunAndIlluminanceColumnsKeepTheTotals'
slow+='|Backends/SkyTraced\.UnobstructedHorizontalIlluminanceWithoutPortals/'
slow+='|Backends/GlazingTraced\.GlazedRoofOpeningUnderTheUniformSky/'
slow+='|optimizer\.SceneExamples\.(ConferenceLightsEndAboveThePodium'
slow+='|ConstrainedFluxAnswerIsFeasibleInAnIndependentSolve)'
slow+='|Backends/HardCases\.FluxesAMillionApartBothReachTheirTargets/"embree"'
slow+='|Backends/GlazingTraced\.SunAndSkyBesideALampTenToTheFiveTimesDimmerEachResolved/)'

steps=${LIGHTSOLVER_SANITIZE_STEPS:-build test}
start=$(date +%s)
if [[ " $steps " == *" build "* ]]; then
  cmake -S . -B "$dir" -G Ninja -DLIGHTSOLVER_SANITIZE=ON -DCMAKE_BUILD_TYPE=Sanitize \
    -DLIGHTSOLVER_BUILD_PYTHON=OFF -DLIGHTSOLVER_BUILD_BENCHMARKS=OFF "$@"
  # Only the test programs (no CLI): the suites that exist in this configuration.
  mapfile -t targets < <(ninja -C "$dir" -t targets all |
    sed -n 's/^\([a-z_]*_tests\): phony$/\1/p' | grep -v '^cmake_')
  cmake --build "$dir" -j "$jobs" --target "${targets[@]}"
  echo "test-sanitize: ${targets[*]}: build $(($(date +%s) - start)) s"
fi
[[ " $steps " == *" test "* ]] || exit 0
built=$(date +%s)

# lavapipe stays loaded for the whole test process: the Vulkan loader unloads the ICD when the
# last instance goes, and the memory LLVM keeps from lavapipe's one-time set-up (reachable from
# the ICD's globals while it is loaded) would then be reported as leaked once per instance.
# Preloading it leaves leak checking on for everything else, ours included.
lvp=$(sed -n 's/.*"library_path": *"\([^"]*\)".*/\1/p' \
  /usr/share/vulkan/icd.d/lvp_icd.x86_64.json 2>/dev/null || true)
if [ -n "$lvp" ] && [ -e "$lvp" ]; then
  export LD_PRELOAD="$lvp${LD_PRELOAD:+:$LD_PRELOAD}"
  export ASAN_OPTIONS="$ASAN_OPTIONS:verify_asan_link_order=0"  # the ICD comes before libasan
fi
# A regular expression CMake cannot compile matches nothing: the run would then leave nothing
# out, or (with -E) run nothing at all. Make sure it names the entries it should.
excluded=$(ctest --test-dir "$dir" -N -R "$slow" | grep -c 'Test *#' || true)
if [ "$excluded" -lt 40 ]; then
  echo "test-sanitize: the slow list matches $excluded entries (a regular expression error?)" >&2
  exit 1
fi
ctest --test-dir "$dir" --output-on-failure -j "$jobs" --timeout 900 -E "$slow"
done_at=$(date +%s)
echo "test-sanitize: tests $((done_at - built)) s"
