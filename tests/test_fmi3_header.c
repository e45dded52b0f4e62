/* SPDX-License-Identifier: BSD-3-Clause */
/* src/fmu/fmi3.h against the FMI 3.0.2 ABI, written out a second time
 * here in plain C types (uint32_t, double, bool, const char *, ...) from
 * the specification's function declarations: each <name>TYPE must be
 * exactly that function type and each declared <name> must have it,
 * else this file does not compile. The run checks the list of functions
 * (75, unique, the same set as here) and the sizes and enum values an
 * importer built elsewhere relies on. Nothing here defines or calls an
 * FMI function: &name appears only in _Generic's unevaluated operand. */
#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>
#include <string.h>

#include "check.h"
#include "fmu/fmi3.h"

/* Parameter types of the spec's signatures, spelled without fmi3 types
 * (the enums have no plain spelling: an enum's underlying integer type
 * is the compiler's choice). */
typedef void *inst;
typedef const uint32_t *vrs; /* const fmi3ValueReference valueReferences[] */
typedef void (*log_cb)(void *, fmi3Status, const char *, const char *);
typedef void (*intermediate_cb)(void *, double, bool, bool, bool, bool, bool *, double *);
typedef void (*clock_cb)(void *);
typedef void (*lock_cb)(void);

/* S(name, return type, parameter types...) for each of the 75 functions. */
#define EXPECTED(S)                                                                            \
  S(fmi3GetVersion, const char *, void)                                                        \
  S(fmi3SetDebugLogging, fmi3Status, inst, bool, size_t, const char *const *)                  \
  S(fmi3InstantiateModelExchange, void *, const char *, const char *, const char *, bool,      \
    bool, void *, log_cb)                                                                      \
  S(fmi3InstantiateCoSimulation, void *, const char *, const char *, const char *, bool, bool, \
    bool, bool, vrs, size_t, void *, log_cb, intermediate_cb)                                  \
  S(fmi3InstantiateScheduledExecution, void *, const char *, const char *, const char *, bool, \
    bool, void *, log_cb, clock_cb, lock_cb, lock_cb)                                          \
  S(fmi3FreeInstance, void, inst)                                                              \
  S(fmi3EnterInitializationMode, fmi3Status, inst, bool, double, double, bool, double)         \
  S(fmi3ExitInitializationMode, fmi3Status, inst)                                              \
  S(fmi3EnterEventMode, fmi3Status, inst)                                                      \
  S(fmi3Terminate, fmi3Status, inst)                                                           \
  S(fmi3Reset, fmi3Status, inst)                                                               \
  S(fmi3GetFloat32, fmi3Status, inst, vrs, size_t, float *, size_t)                            \
  S(fmi3GetFloat64, fmi3Status, inst, vrs, size_t, double *, size_t)                           \
  S(fmi3GetInt8, fmi3Status, inst, vrs, size_t, int8_t *, size_t)                              \
  S(fmi3GetUInt8, fmi3Status, inst, vrs, size_t, uint8_t *, size_t)                            \
  S(fmi3GetInt16, fmi3Status, inst, vrs, size_t, int16_t *, size_t)                            \
  S(fmi3GetUInt16, fmi3Status, inst, vrs, size_t, uint16_t *, size_t)                          \
  S(fmi3GetInt32, fmi3Status, inst, vrs, size_t, int32_t *, size_t)                            \
  S(fmi3GetUInt32, fmi3Status, inst, vrs, size_t, uint32_t *, size_t)                          \
  S(fmi3GetInt64, fmi3Status, inst, vrs, size_t, int64_t *, size_t)                            \
  S(fmi3GetUInt64, fmi3Status, inst, vrs, size_t, uint64_t *, size_t)                          \
  S(fmi3GetBoolean, fmi3Status, inst, vrs, size_t, bool *, size_t)                             \
  S(fmi3GetString, fmi3Status, inst, vrs, size_t, const char **, size_t)                       \
  S(fmi3GetBinary, fmi3Status, inst, vrs, size_t, size_t *, const uint8_t **, size_t)          \
  S(fmi3GetClock, fmi3Status, inst, vrs, size_t, bool *)                                       \
  S(fmi3SetFloat32, fmi3Status, inst, vrs, size_t, const float *, size_t)                      \
  S(fmi3SetFloat64, fmi3Status, inst, vrs, size_t, const double *, size_t)                     \
  S(fmi3SetInt8, fmi3Status, inst, vrs, size_t, const int8_t *, size_t)                        \
  S(fmi3SetUInt8, fmi3Status, inst, vrs, size_t, const uint8_t *, size_t)                      \
  S(fmi3SetInt16, fmi3Status, inst, vrs, size_t, const int16_t *, size_t)                      \
  S(fmi3SetUInt16, fmi3Status, inst, vrs, size_t, const uint16_t *, size_t)                    \
  S(fmi3SetInt32, fmi3Status, inst, vrs, size_t, const int32_t *, size_t)                      \
  S(fmi3SetUInt32, fmi3Status, inst, vrs, size_t, const uint32_t *, size_t)                    \
  S(fmi3SetInt64, fmi3Status, inst, vrs, size_t, const int64_t *, size_t)                      \
  S(fmi3SetUInt64, fmi3Status, inst, vrs, size_t, const uint64_t *, size_t)                    \
  S(fmi3SetBoolean, fmi3Status, inst, vrs, size_t, const bool *, size_t)                       \
  S(fmi3SetString, fmi3Status, inst, vrs, size_t, const char *const *, size_t)                 \
  S(fmi3SetBinary, fmi3Status, inst, vrs, size_t, const size_t *, const uint8_t *const *,      \
    size_t)                                                                                    \
  S(fmi3SetClock, fmi3Status, inst, vrs, size_t, const bool *)                                 \
  S(fmi3GetNumberOfVariableDependencies, fmi3Status, inst, uint32_t, size_t *)                 \
  S(fmi3GetVariableDependencies, fmi3Status, inst, uint32_t, size_t *, uint32_t *, size_t *,   \
    fmi3DependencyKind *, size_t)                                                              \
  S(fmi3GetFMUState, fmi3Status, inst, void **)                                                \
  S(fmi3SetFMUState, fmi3Status, inst, void *)                                                 \
  S(fmi3FreeFMUState, fmi3Status, inst, void **)                                               \
  S(fmi3SerializedFMUStateSize, fmi3Status, inst, void *, size_t *)                            \
  S(fmi3SerializeFMUState, fmi3Status, inst, void *, uint8_t *, size_t)                        \
  S(fmi3DeserializeFMUState, fmi3Status, inst, const uint8_t *, size_t, void **)               \
  S(fmi3GetDirectionalDerivative, fmi3Status, inst, vrs, size_t, vrs, size_t, const double *,  \
    size_t, double *, size_t)                                                                  \
  S(fmi3GetAdjointDerivative, fmi3Status, inst, vrs, size_t, vrs, size_t, const double *,      \
    size_t, double *, size_t)                                                                  \
  S(fmi3EnterConfigurationMode, fmi3Status, inst)                                              \
  S(fmi3ExitConfigurationMode, fmi3Status, inst)                                               \
  S(fmi3GetIntervalDecimal, fmi3Status, inst, vrs, size_t, double *, fmi3IntervalQualifier *)  \
  S(fmi3GetIntervalFraction, fmi3Status, inst, vrs, size_t, uint64_t *, uint64_t *,            \
    fmi3IntervalQualifier *)                                                                   \
  S(fmi3GetShiftDecimal, fmi3Status, inst, vrs, size_t, double *)                              \
  S(fmi3GetShiftFraction, fmi3Status, inst, vrs, size_t, uint64_t *, uint64_t *)               \
  S(fmi3SetIntervalDecimal, fmi3Status, inst, vrs, size_t, const double *)                     \
  S(fmi3SetIntervalFraction, fmi3Status, inst, vrs, size_t, const uint64_t *,                  \
    const uint64_t *)                                                                          \
  S(fmi3SetShiftDecimal, fmi3Status, inst, vrs, size_t, const double *)                        \
  S(fmi3SetShiftFraction, fmi3Status, inst, vrs, size_t, const uint64_t *, const uint64_t *)   \
  S(fmi3EvaluateDiscreteStates, fmi3Status, inst)                                              \
  S(fmi3UpdateDiscreteStates, fmi3Status, inst, bool *, bool *, bool *, bool *, bool *,        \
    double *)                                                                                  \
  S(fmi3EnterContinuousTimeMode, fmi3Status, inst)                                             \
  S(fmi3CompletedIntegratorStep, fmi3Status, inst, bool, bool *, bool *)                       \
  S(fmi3SetTime, fmi3Status, inst, double)                                                     \
  S(fmi3SetContinuousStates, fmi3Status, inst, const double *, size_t)                         \
  S(fmi3GetContinuousStateDerivatives, fmi3Status, inst, double *, size_t)                     \
  S(fmi3GetEventIndicators, fmi3Status, inst, double *, size_t)                                \
  S(fmi3GetContinuousStates, fmi3Status, inst, double *, size_t)                               \
  S(fmi3GetNominalsOfContinuousStates, fmi3Status, inst, double *, size_t)                     \
  S(fmi3GetNumberOfEventIndicators, fmi3Status, inst, size_t *)                                \
  S(fmi3GetNumberOfContinuousStates, fmi3Status, inst, size_t *)                               \
  S(fmi3EnterStepMode, fmi3Status, inst)                                                       \
  S(fmi3GetOutputDerivatives, fmi3Status, inst, vrs, size_t, const int32_t *, double *,        \
    size_t)                                                                                    \
  S(fmi3DoStep, fmi3Status, inst, double, double, bool, bool *, bool *, bool *, double *)      \
  S(fmi3ActivateModelPartition, fmi3Status, inst, uint32_t, double)

/* The typedef is that function type; the declaration has the typedef. */
#define CHECK_SIGNATURE(name, ret, ...)                                                        \
  _Static_assert(_Generic((name##TYPE *)0, ret(*)(__VA_ARGS__) : 1, default : 0),              \
                 #name "TYPE differs from the specification's signature");                     \
  _Static_assert(_Generic(&name, name##TYPE * : 1, default : 0),                               \
                 #name " is not declared with " #name "TYPE");
EXPECTED(CHECK_SIGNATURE)

/* The callbacks, the same way. */
_Static_assert(_Generic((fmi3LogMessageCallback)0, log_cb : 1, default : 0), "logMessage");
_Static_assert(_Generic((fmi3IntermediateUpdateCallback)0, intermediate_cb : 1, default : 0),
               "intermediateUpdate");
_Static_assert(_Generic((fmi3ClockUpdateCallback)0, clock_cb : 1, default : 0), "clockUpdate");
_Static_assert(_Generic((fmi3LockPreemptionCallback)0, lock_cb : 1, default : 0),
               "lockPreemption");
_Static_assert(_Generic((fmi3UnlockPreemptionCallback)0, lock_cb : 1, default : 0),
               "unlockPreemption");

/* The base types are those C types (not merely of the same size: bool
 * is not unsigned char, int8_t is not char). */
#define IS(type, expected) _Generic((type *)0, expected * : 1, default : 0)
_Static_assert(IS(fmi3Instance, void *) && IS(fmi3InstanceEnvironment, void *) &&
                   IS(fmi3FMUState, void *),
               "handles");
_Static_assert(IS(fmi3ValueReference, uint32_t), "fmi3ValueReference");
_Static_assert(IS(fmi3Float32, float) && IS(fmi3Float64, double), "floats");
_Static_assert(IS(fmi3Int8, int8_t) && IS(fmi3UInt8, uint8_t) && IS(fmi3Int16, int16_t) &&
                   IS(fmi3UInt16, uint16_t) && IS(fmi3Int32, int32_t) &&
                   IS(fmi3UInt32, uint32_t) && IS(fmi3Int64, int64_t) &&
                   IS(fmi3UInt64, uint64_t),
               "integers");
_Static_assert(IS(fmi3Boolean, bool) && IS(fmi3Clock, bool), "fmi3Boolean, fmi3Clock");
_Static_assert(IS(fmi3Char, char) && IS(fmi3String, const char *), "strings");
_Static_assert(IS(fmi3Byte, uint8_t) && IS(fmi3Binary, const uint8_t *), "binary");

#define NAME_OF(name) #name,
#define EXPECTED_NAME(name, ...) #name,
static const char *const header_names[] = {FB_FMI3_FOR_EACH_FUNCTION(NAME_OF)};
static const char *const expected_names[] = {EXPECTED(EXPECTED_NAME)};
#define N_HEADER (sizeof header_names / sizeof header_names[0])
#define N_EXPECTED (sizeof expected_names / sizeof expected_names[0])

static int listed(const char *const *list, size_t n, const char *name)
{
  size_t count = 0;
  for (size_t i = 0; i < n; ++i)
    count += !strcmp(list[i], name);
  return (int)count;
}

static void test_function_list(void)
{
  CHECK(FB_FMI3_FUNCTION_COUNT == 75);
  CHECK(N_HEADER == FB_FMI3_FUNCTION_COUNT);
  CHECK(N_EXPECTED == 75);
  for (size_t i = 0; i < N_HEADER; ++i) {
    CHECK(listed(header_names, N_HEADER, header_names[i]) == 1);
    CHECK(listed(expected_names, N_EXPECTED, header_names[i]) == 1);
    if (listed(expected_names, N_EXPECTED, header_names[i]) != 1)
      fprintf(stderr, "  %s of the header's list is not among the expected\n", header_names[i]);
  }
  for (size_t i = 0; i < N_EXPECTED; ++i) {
    int n = listed(header_names, N_HEADER, expected_names[i]);
    CHECK(n == 1);
    if (n != 1)
      fprintf(stderr, "  %s is in the header's list %d times\n", expected_names[i], n);
    CHECK(listed(expected_names, N_EXPECTED, expected_names[i]) == 1);
    CHECK(!strncmp(expected_names[i], "fmi3", 4));
  }
}

static void test_sizes(void)
{
  CHECK(sizeof(fmi3Boolean) == 1);
  CHECK(sizeof(fmi3Clock) == 1);
  CHECK(sizeof(fmi3Char) == 1);
  CHECK(sizeof(fmi3Byte) == 1);
  CHECK(sizeof(fmi3ValueReference) == 4);
  CHECK(sizeof(fmi3Float32) == 4);
  CHECK(sizeof(fmi3Float64) == 8);
  CHECK(sizeof(fmi3Int8) == 1 && sizeof(fmi3UInt8) == 1);
  CHECK(sizeof(fmi3Int16) == 2 && sizeof(fmi3UInt16) == 2);
  CHECK(sizeof(fmi3Int32) == 4 && sizeof(fmi3UInt32) == 4);
  CHECK(sizeof(fmi3Int64) == 8 && sizeof(fmi3UInt64) == 8);
  CHECK(sizeof(fmi3Instance) == sizeof(void *));
  CHECK(sizeof(fmi3String) == sizeof(void *) && sizeof(fmi3Binary) == sizeof(void *));
  /* The enums pass as int-sized arguments and array elements. */
  CHECK(sizeof(fmi3Status) == sizeof(int));
  CHECK(sizeof(fmi3DependencyKind) == sizeof(int));
  CHECK(sizeof(fmi3IntervalQualifier) == sizeof(int));
}

static void test_enum_values(void)
{
  CHECK(fmi3OK == 0);
  CHECK(fmi3Warning == 1);
  CHECK(fmi3Discard == 2);
  CHECK(fmi3Error == 3);
  CHECK(fmi3Fatal == 4);

  CHECK(fmi3Independent == 0);
  CHECK(fmi3Constant == 1);
  CHECK(fmi3Fixed == 2);
  CHECK(fmi3Tunable == 3);
  CHECK(fmi3Discrete == 4);
  CHECK(fmi3Dependent == 5);

  CHECK(fmi3IntervalNotYetKnown == 0);
  CHECK(fmi3IntervalUnchanged == 1);
  CHECK(fmi3IntervalChanged == 2);

  CHECK(fmi3True == 1 && fmi3False == 0);
  CHECK(fmi3ClockActive == 1 && fmi3ClockInactive == 0);
  CHECK(!strcmp(FB_FMI3_VERSION, "3.0"));
}

int main(void)
{
  test_function_list();
  test_sizes();
  test_enum_values();
  return check_report("test_fmi3_header");
}
