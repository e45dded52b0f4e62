/* SPDX-License-Identifier: BSD-3-Clause */
/* The FMI 3.0 C API (Functional Mock-up Interface, version 3.0.2) as
 * flexbond's FMU (src/fmu) exports it and the test importer calls it,
 * declared here from the text of the specification (the AsciiDoc of
 * modelica/fmi-standard, tag v3.0.2), not taken from the standard's
 * header files:
 *   2.2.3  Platform Dependent Definitions  - handles and value types
 *   2.2.4  Status Returned by Functions    - fmi3Status
 *   2.2.5  Inquire Version Number          - fmi3GetVersion
 *   2.2.7  Variables                       - get/set values, FMU state
 *   2.2.8  Clocks (2.2.8.4 Clocks specific API) - intervals and shifts
 *   2.2.9  Dependencies of Variables
 *   2.2.12 Getting Partial Derivatives     - directional and adjoint
 *   2.3    State Machine and Semantics     - instantiation, modes
 *   3.2    Model Exchange API;  4.1.2 and 4.2 Co-Simulation;
 *   5.1.2  Preemption Support and 5.2 Scheduled Execution API.
 * The types are meant to be ABI-identical to the standard's, so an
 * importer built on the standard headers (FMPy, for one) can load our
 * FMU and our importer can load anyone's.
 *
 * The API has 75 functions (FB_FMI3_FUNCTION_COUNT): 61 common to all
 * interface types, 10 for Model Exchange, 3 for Co-Simulation and 1 for
 * Scheduled Execution. Each has a function type <name>TYPE, as the
 * standard names them (an importer holds a <name>TYPE * looked up by
 * name), and a declaration of <name> with that type, so an FMU that
 * defines it is checked by the compiler against the exact signature.
 * FB_FMI3_FOR_EACH_FUNCTION lists all of them in the specification's
 * order. No function prefix (FMI3_FUNCTION_PREFIX) is supported: the
 * FMU exports the plain names, as a binary FMU must. */
#ifndef FLEXBOND_FMU_FMI3_H
#define FLEXBOND_FMU_FMI3_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

/* What fmi3GetVersion of an FMU built on this header returns. */
#define FB_FMI3_VERSION "3.0"

/* Marks the exported FMI functions (may be defined before inclusion). */
#ifndef FB_FMI3_EXPORT
#if defined(_WIN32) || defined(__CYGWIN__)
#define FB_FMI3_EXPORT __declspec(dllexport)
#elif defined(__GNUC__) || defined(__clang__)
#define FB_FMI3_EXPORT __attribute__((visibility("default")))
#else
#define FB_FMI3_EXPORT
#endif
#endif

/* ---- 2.2.3: handles and value types ---------------------------------- */

typedef void *fmi3Instance;            /* the FMU's own data of one instance */
typedef void *fmi3InstanceEnvironment; /* the importer's, passed back to callbacks */
typedef void *fmi3FMUState;            /* a saved internal state of an instance */
typedef uint32_t fmi3ValueReference;   /* valueReference of modelDescription.xml */

typedef float fmi3Float32;
typedef double fmi3Float64;
typedef int8_t fmi3Int8;
typedef uint8_t fmi3UInt8;
typedef int16_t fmi3Int16;
typedef uint16_t fmi3UInt16;
typedef int32_t fmi3Int32;
typedef uint32_t fmi3UInt32;
typedef int64_t fmi3Int64;
typedef uint64_t fmi3UInt64;
typedef bool fmi3Boolean;
typedef char fmi3Char;
typedef const fmi3Char *fmi3String; /* NUL-terminated UTF-8 */
typedef uint8_t fmi3Byte;
typedef const fmi3Byte *fmi3Binary; /* its length travels beside it (valueSizes) */
typedef bool fmi3Clock;

#define fmi3True true
#define fmi3False false
#define fmi3ClockActive true
#define fmi3ClockInactive false

/* ---- 2.2.4, 2.2.9, 2.2.8.4: enumerations ----------------------------- */

typedef enum {
  fmi3OK = 0,      /* done; outputs defined */
  fmi3Warning = 1, /* done with a logged, non-critical problem; outputs defined */
  fmi3Discard = 2, /* not done, instance unchanged; the importer may try otherwise */
  fmi3Error = 3,   /* failed; go on only after fmi3SetFMUState or fmi3Reset */
  fmi3Fatal = 4    /* every instance of the FMU is corrupt; call nothing more */
} fmi3Status;

/* How a dependent variable depends on an independent one
 * (fmi3GetVariableDependencies; the dependencyKind attribute). */
typedef enum {
  fmi3Independent = 0,
  fmi3Constant = 1,
  fmi3Fixed = 2,
  fmi3Tunable = 3,
  fmi3Discrete = 4,
  fmi3Dependent = 5
} fmi3DependencyKind;

/* What fmi3GetInterval* says of a Clock's interval. */
typedef enum {
  fmi3IntervalNotYetKnown = 0,
  fmi3IntervalUnchanged = 1,
  fmi3IntervalChanged = 2
} fmi3IntervalQualifier;

/* ---- callbacks the importer passes at instantiation (2.3.1, 4.2.2,
 *      5.1.2, 5.2.2) ---------------------------------------------------- */

typedef void (*fmi3LogMessageCallback)(fmi3InstanceEnvironment instanceEnvironment,
                                       fmi3Status status, fmi3String category,
                                       fmi3String message);

/* Co-Simulation: the FMU reached an intermediate point of fmi3DoStep. */
typedef void (*fmi3IntermediateUpdateCallback)(
    fmi3InstanceEnvironment instanceEnvironment, fmi3Float64 intermediateUpdateTime,
    fmi3Boolean intermediateVariableSetRequested, fmi3Boolean intermediateVariableGetAllowed,
    fmi3Boolean intermediateStepFinished, fmi3Boolean canReturnEarly,
    fmi3Boolean *earlyReturnRequested, fmi3Float64 *earlyReturnTime);

/* Scheduled Execution: an internal Clock ticked (or a countdown Clock's
 * interval changed). */
typedef void (*fmi3ClockUpdateCallback)(fmi3InstanceEnvironment instanceEnvironment);

/* Scheduled Execution: bracket a critical section of the FMU. */
typedef void (*fmi3LockPreemptionCallback)(void);
typedef void (*fmi3UnlockPreemptionCallback)(void);

/* ---- common functions ------------------------------------------------- */

/* 2.2.5: FB_FMI3_VERSION of the header the FMU was built with. */
typedef const char *fmi3GetVersionTYPE(void);

/* 2.3.1: logging on or off, for all categories (nCategories 0) or those. */
typedef fmi3Status fmi3SetDebugLoggingTYPE(fmi3Instance instance, fmi3Boolean loggingOn,
                                           size_t nCategories, const fmi3String categories[]);

/* 2.3.1: one instantiation function per interface type; NULL on failure. */
typedef fmi3Instance fmi3InstantiateModelExchangeTYPE(
    fmi3String instanceName, fmi3String instantiationToken, fmi3String resourcePath,
    fmi3Boolean visible, fmi3Boolean loggingOn, fmi3InstanceEnvironment instanceEnvironment,
    fmi3LogMessageCallback logMessage);

typedef fmi3Instance fmi3InstantiateCoSimulationTYPE(
    fmi3String instanceName, fmi3String instantiationToken, fmi3String resourcePath,
    fmi3Boolean visible, fmi3Boolean loggingOn, fmi3Boolean eventModeUsed,
    fmi3Boolean earlyReturnAllowed, const fmi3ValueReference requiredIntermediateVariables[],
    size_t nRequiredIntermediateVariables, fmi3InstanceEnvironment instanceEnvironment,
    fmi3LogMessageCallback logMessage, fmi3IntermediateUpdateCallback intermediateUpdate);

typedef fmi3Instance fmi3InstantiateScheduledExecutionTYPE(
    fmi3String instanceName, fmi3String instantiationToken, fmi3String resourcePath,
    fmi3Boolean visible, fmi3Boolean loggingOn, fmi3InstanceEnvironment instanceEnvironment,
    fmi3LogMessageCallback logMessage, fmi3ClockUpdateCallback clockUpdate,
    fmi3LockPreemptionCallback lockPreemption, fmi3UnlockPreemptionCallback unlockPreemption);

/* 2.3.1: frees the instance (NULL allowed). */
typedef void fmi3FreeInstanceTYPE(fmi3Instance instance);

/* 2.3.2, 2.3.3: into and out of Initialization Mode. */
typedef fmi3Status fmi3EnterInitializationModeTYPE(fmi3Instance instance,
                                                   fmi3Boolean toleranceDefined,
                                                   fmi3Float64 tolerance, fmi3Float64 startTime,
                                                   fmi3Boolean stopTimeDefined,
                                                   fmi3Float64 stopTime);
typedef fmi3Status fmi3ExitInitializationModeTYPE(fmi3Instance instance);

/* 3.2.1 (ME), 4.2.1 (CS with eventModeUsed): into Event Mode. */
typedef fmi3Status fmi3EnterEventModeTYPE(fmi3Instance instance);

/* 2.3.4: to Terminated; 2.3.1: back to Instantiated. */
typedef fmi3Status fmi3TerminateTYPE(fmi3Instance instance);
typedef fmi3Status fmi3ResetTYPE(fmi3Instance instance);

/* 2.2.7.2: fmi3Get{Type} of the variables valueReferences[0..n), with
 * nValues the number of values in all of them (arrays serialized).
 * Binary values come with their sizes; Clocks have one value each. */
typedef fmi3Status fmi3GetFloat32TYPE(fmi3Instance instance,
                                      const fmi3ValueReference valueReferences[],
                                      size_t nValueReferences, fmi3Float32 values[],
                                      size_t nValues);
typedef fmi3Status fmi3GetFloat64TYPE(fmi3Instance instance,
                                      const fmi3ValueReference valueReferences[],
                                      size_t nValueReferences, fmi3Float64 values[],
                                      size_t nValues);
typedef fmi3Status fmi3GetInt8TYPE(fmi3Instance instance,
                                   const fmi3ValueReference valueReferences[],
                                   size_t nValueReferences, fmi3Int8 values[], size_t nValues);
typedef fmi3Status fmi3GetUInt8TYPE(fmi3Instance instance,
                                    const fmi3ValueReference valueReferences[],
                                    size_t nValueReferences, fmi3UInt8 values[],
                                    size_t nValues);
typedef fmi3Status fmi3GetInt16TYPE(fmi3Instance instance,
                                    const fmi3ValueReference valueReferences[],
                                    size_t nValueReferences, fmi3Int16 values[],
                                    size_t nValues);
typedef fmi3Status fmi3GetUInt16TYPE(fmi3Instance instance,
                                     const fmi3ValueReference valueReferences[],
                                     size_t nValueReferences, fmi3UInt16 values[],
                                     size_t nValues);
typedef fmi3Status fmi3GetInt32TYPE(fmi3Instance instance,
                                    const fmi3ValueReference valueReferences[],
                                    size_t nValueReferences, fmi3Int32 values[],
                                    size_t nValues);
typedef fmi3Status fmi3GetUInt32TYPE(fmi3Instance instance,
                                     const fmi3ValueReference valueReferences[],
                                     size_t nValueReferences, fmi3UInt32 values[],
                                     size_t nValues);
typedef fmi3Status fmi3GetInt64TYPE(fmi3Instance instance,
                                    const fmi3ValueReference valueReferences[],
                                    size_t nValueReferences, fmi3Int64 values[],
                                    size_t nValues);
typedef fmi3Status fmi3GetUInt64TYPE(fmi3Instance instance,
                                     const fmi3ValueReference valueReferences[],
                                     size_t nValueReferences, fmi3UInt64 values[],
                                     size_t nValues);
typedef fmi3Status fmi3GetBooleanTYPE(fmi3Instance instance,
                                      const fmi3ValueReference valueReferences[],
                                      size_t nValueReferences, fmi3Boolean values[],
                                      size_t nValues);
typedef fmi3Status fmi3GetStringTYPE(fmi3Instance instance,
                                     const fmi3ValueReference valueReferences[],
                                     size_t nValueReferences, fmi3String values[],
                                     size_t nValues);
typedef fmi3Status fmi3GetBinaryTYPE(fmi3Instance instance,
                                     const fmi3ValueReference valueReferences[],
                                     size_t nValueReferences, size_t valueSizes[],
                                     fmi3Binary values[], size_t nValues);
typedef fmi3Status fmi3GetClockTYPE(fmi3Instance instance,
                                    const fmi3ValueReference valueReferences[],
                                    size_t nValueReferences, fmi3Clock values[]);

/* 2.2.7.2: fmi3Set{Type}, the same layout with the values read. */
typedef fmi3Status fmi3SetFloat32TYPE(fmi3Instance instance,
                                      const fmi3ValueReference valueReferences[],
                                      size_t nValueReferences, const fmi3Float32 values[],
                                      size_t nValues);
typedef fmi3Status fmi3SetFloat64TYPE(fmi3Instance instance,
                                      const fmi3ValueReference valueReferences[],
                                      size_t nValueReferences, const fmi3Float64 values[],
                                      size_t nValues);
typedef fmi3Status fmi3SetInt8TYPE(fmi3Instance instance,
                                   const fmi3ValueReference valueReferences[],
                                   size_t nValueReferences, const fmi3Int8 values[],
                                   size_t nValues);
typedef fmi3Status fmi3SetUInt8TYPE(fmi3Instance instance,
                                    const fmi3ValueReference valueReferences[],
                                    size_t nValueReferences, const fmi3UInt8 values[],
                                    size_t nValues);
typedef fmi3Status fmi3SetInt16TYPE(fmi3Instance instance,
                                    const fmi3ValueReference valueReferences[],
                                    size_t nValueReferences, const fmi3Int16 values[],
                                    size_t nValues);
typedef fmi3Status fmi3SetUInt16TYPE(fmi3Instance instance,
                                     const fmi3ValueReference valueReferences[],
                                     size_t nValueReferences, const fmi3UInt16 values[],
                                     size_t nValues);
typedef fmi3Status fmi3SetInt32TYPE(fmi3Instance instance,
                                    const fmi3ValueReference valueReferences[],
                                    size_t nValueReferences, const fmi3Int32 values[],
                                    size_t nValues);
typedef fmi3Status fmi3SetUInt32TYPE(fmi3Instance instance,
                                     const fmi3ValueReference valueReferences[],
                                     size_t nValueReferences, const fmi3UInt32 values[],
                                     size_t nValues);
typedef fmi3Status fmi3SetInt64TYPE(fmi3Instance instance,
                                    const fmi3ValueReference valueReferences[],
                                    size_t nValueReferences, const fmi3Int64 values[],
                                    size_t nValues);
typedef fmi3Status fmi3SetUInt64TYPE(fmi3Instance instance,
                                     const fmi3ValueReference valueReferences[],
                                     size_t nValueReferences, const fmi3UInt64 values[],
                                     size_t nValues);
typedef fmi3Status fmi3SetBooleanTYPE(fmi3Instance instance,
                                      const fmi3ValueReference valueReferences[],
                                      size_t nValueReferences, const fmi3Boolean values[],
                                      size_t nValues);
typedef fmi3Status fmi3SetStringTYPE(fmi3Instance instance,
                                     const fmi3ValueReference valueReferences[],
                                     size_t nValueReferences, const fmi3String values[],
                                     size_t nValues);
typedef fmi3Status fmi3SetBinaryTYPE(fmi3Instance instance,
                                     const fmi3ValueReference valueReferences[],
                                     size_t nValueReferences, const size_t valueSizes[],
                                     const fmi3Binary values[], size_t nValues);
typedef fmi3Status fmi3SetClockTYPE(fmi3Instance instance,
                                    const fmi3ValueReference valueReferences[],
                                    size_t nValueReferences, const fmi3Clock values[]);

/* 2.2.9: what the variable `dependent` depends on, one entry per
 * dependency (nDependencies from the first function). */
typedef fmi3Status fmi3GetNumberOfVariableDependenciesTYPE(fmi3Instance instance,
                                                           fmi3ValueReference valueReference,
                                                           size_t *nDependencies);
typedef fmi3Status fmi3GetVariableDependenciesTYPE(
    fmi3Instance instance, fmi3ValueReference dependent, size_t elementIndicesOfDependent[],
    fmi3ValueReference independents[], size_t elementIndicesOfIndependents[],
    fmi3DependencyKind dependencyKinds[], size_t nDependencies);

/* 2.2.7.4: saving, restoring and serializing the complete FMU state. */
typedef fmi3Status fmi3GetFMUStateTYPE(fmi3Instance instance, fmi3FMUState *FMUState);
typedef fmi3Status fmi3SetFMUStateTYPE(fmi3Instance instance, fmi3FMUState FMUState);
typedef fmi3Status fmi3FreeFMUStateTYPE(fmi3Instance instance, fmi3FMUState *FMUState);
typedef fmi3Status fmi3SerializedFMUStateSizeTYPE(fmi3Instance instance, fmi3FMUState FMUState,
                                                  size_t *size);
typedef fmi3Status fmi3SerializeFMUStateTYPE(fmi3Instance instance, fmi3FMUState FMUState,
                                             fmi3Byte serializedState[], size_t size);
typedef fmi3Status fmi3DeserializeFMUStateTYPE(fmi3Instance instance,
                                               const fmi3Byte serializedState[], size_t size,
                                               fmi3FMUState *FMUState);

/* 2.2.12: sensitivity = J * seed (directional) or seed^T * J (adjoint),
 * J the partial derivatives of the unknowns by the knowns. */
typedef fmi3Status
fmi3GetDirectionalDerivativeTYPE(fmi3Instance instance, const fmi3ValueReference unknowns[],
                                 size_t nUnknowns, const fmi3ValueReference knowns[],
                                 size_t nKnowns, const fmi3Float64 seed[], size_t nSeed,
                                 fmi3Float64 sensitivity[], size_t nSensitivity);
typedef fmi3Status
fmi3GetAdjointDerivativeTYPE(fmi3Instance instance, const fmi3ValueReference unknowns[],
                             size_t nUnknowns, const fmi3ValueReference knowns[],
                             size_t nKnowns, const fmi3Float64 seed[], size_t nSeed,
                             fmi3Float64 sensitivity[], size_t nSensitivity);

/* 2.3.2, 2.3.6: into and out of (Re)configuration Mode, where structural
 * parameters change. */
typedef fmi3Status fmi3EnterConfigurationModeTYPE(fmi3Instance instance);
typedef fmi3Status fmi3ExitConfigurationModeTYPE(fmi3Instance instance);

/* 2.2.8.4: Clock intervals and shifts, as a decimal (seconds) or as a
 * fraction counter / resolution. */
typedef fmi3Status fmi3GetIntervalDecimalTYPE(fmi3Instance instance,
                                              const fmi3ValueReference valueReferences[],
                                              size_t nValueReferences, fmi3Float64 intervals[],
                                              fmi3IntervalQualifier qualifiers[]);
typedef fmi3Status fmi3GetIntervalFractionTYPE(fmi3Instance instance,
                                               const fmi3ValueReference valueReferences[],
                                               size_t nValueReferences, fmi3UInt64 counters[],
                                               fmi3UInt64 resolutions[],
                                               fmi3IntervalQualifier qualifiers[]);
typedef fmi3Status fmi3GetShiftDecimalTYPE(fmi3Instance instance,
                                           const fmi3ValueReference valueReferences[],
                                           size_t nValueReferences, fmi3Float64 shifts[]);
typedef fmi3Status fmi3GetShiftFractionTYPE(fmi3Instance instance,
                                            const fmi3ValueReference valueReferences[],
                                            size_t nValueReferences, fmi3UInt64 counters[],
                                            fmi3UInt64 resolutions[]);
typedef fmi3Status fmi3SetIntervalDecimalTYPE(fmi3Instance instance,
                                              const fmi3ValueReference valueReferences[],
                                              size_t nValueReferences,
                                              const fmi3Float64 intervals[]);
typedef fmi3Status fmi3SetIntervalFractionTYPE(fmi3Instance instance,
                                               const fmi3ValueReference valueReferences[],
                                               size_t nValueReferences,
                                               const fmi3UInt64 counters[],
                                               const fmi3UInt64 resolutions[]);
typedef fmi3Status fmi3SetShiftDecimalTYPE(fmi3Instance instance,
                                           const fmi3ValueReference valueReferences[],
                                           size_t nValueReferences, const fmi3Float64 shifts[]);
typedef fmi3Status fmi3SetShiftFractionTYPE(fmi3Instance instance,
                                            const fmi3ValueReference valueReferences[],
                                            size_t nValueReferences,
                                            const fmi3UInt64 counters[],
                                            const fmi3UInt64 resolutions[]);

/* 2.3.5: Event Mode - evaluate the discrete states, or update them and
 * tell the importer what follows. */
typedef fmi3Status fmi3EvaluateDiscreteStatesTYPE(fmi3Instance instance);
typedef fmi3Status fmi3UpdateDiscreteStatesTYPE(fmi3Instance instance,
                                                fmi3Boolean *discreteStatesNeedUpdate,
                                                fmi3Boolean *terminateSimulation,
                                                fmi3Boolean *nominalsOfContinuousStatesChanged,
                                                fmi3Boolean *valuesOfContinuousStatesChanged,
                                                fmi3Boolean *nextEventTimeDefined,
                                                fmi3Float64 *nextEventTime);

/* ---- Model Exchange (2.3.2, 2.3.3, 2.3.5, 3.2.1) ---------------------- */

typedef fmi3Status fmi3EnterContinuousTimeModeTYPE(fmi3Instance instance);
typedef fmi3Status fmi3CompletedIntegratorStepTYPE(fmi3Instance instance,
                                                   fmi3Boolean noSetFMUStatePriorToCurrentPoint,
                                                   fmi3Boolean *enterEventMode,
                                                   fmi3Boolean *terminateSimulation);
typedef fmi3Status fmi3SetTimeTYPE(fmi3Instance instance, fmi3Float64 time);
typedef fmi3Status fmi3SetContinuousStatesTYPE(fmi3Instance instance,
                                               const fmi3Float64 continuousStates[],
                                               size_t nContinuousStates);
typedef fmi3Status fmi3GetContinuousStateDerivativesTYPE(fmi3Instance instance,
                                                         fmi3Float64 derivatives[],
                                                         size_t nContinuousStates);
typedef fmi3Status fmi3GetEventIndicatorsTYPE(fmi3Instance instance,
                                              fmi3Float64 eventIndicators[],
                                              size_t nEventIndicators);
typedef fmi3Status fmi3GetContinuousStatesTYPE(fmi3Instance instance,
                                               fmi3Float64 continuousStates[],
                                               size_t nContinuousStates);
typedef fmi3Status fmi3GetNominalsOfContinuousStatesTYPE(fmi3Instance instance,
                                                         fmi3Float64 nominals[],
                                                         size_t nContinuousStates);
typedef fmi3Status fmi3GetNumberOfEventIndicatorsTYPE(fmi3Instance instance,
                                                      size_t *nEventIndicators);
typedef fmi3Status fmi3GetNumberOfContinuousStatesTYPE(fmi3Instance instance,
                                                       size_t *nContinuousStates);

/* ---- Co-Simulation (2.3.5, 4.1.2, 4.2.1) ------------------------------ */

typedef fmi3Status fmi3EnterStepModeTYPE(fmi3Instance instance);
/* Derivatives of order orders[i] of the continuous outputs. */
typedef fmi3Status fmi3GetOutputDerivativesTYPE(fmi3Instance instance,
                                                const fmi3ValueReference valueReferences[],
                                                size_t nValueReferences,
                                                const fmi3Int32 orders[], fmi3Float64 values[],
                                                size_t nValues);
typedef fmi3Status fmi3DoStepTYPE(fmi3Instance instance, fmi3Float64 currentCommunicationPoint,
                                  fmi3Float64 communicationStepSize,
                                  fmi3Boolean noSetFMUStatePriorToCurrentPoint,
                                  fmi3Boolean *eventHandlingNeeded,
                                  fmi3Boolean *terminateSimulation, fmi3Boolean *earlyReturn,
                                  fmi3Float64 *lastSuccessfulTime);

/* ---- Scheduled Execution (5.2.1) --------------------------------------- */

typedef fmi3Status fmi3ActivateModelPartitionTYPE(fmi3Instance instance,
                                                  fmi3ValueReference clockReference,
                                                  fmi3Float64 activationTime);

/* ---- the list and the declarations ------------------------------------ */

/* X(name) for each of the 75 functions, in the specification's order:
 * common, then Model Exchange, Co-Simulation, Scheduled Execution. */
#define FB_FMI3_FOR_EACH_FUNCTION(X)                                                           \
  X(fmi3GetVersion)                                                                            \
  X(fmi3SetDebugLogging)                                                                       \
  X(fmi3InstantiateModelExchange)                                                              \
  X(fmi3InstantiateCoSimulation)                                                               \
  X(fmi3InstantiateScheduledExecution)                                                         \
  X(fmi3FreeInstance)                                                                          \
  X(fmi3EnterInitializationMode)                                                               \
  X(fmi3ExitInitializationMode)                                                                \
  X(fmi3EnterEventMode)                                                                        \
  X(fmi3Terminate)                                                                             \
  X(fmi3Reset)                                                                                 \
  X(fmi3GetFloat32)                                                                            \
  X(fmi3GetFloat64)                                                                            \
  X(fmi3GetInt8)                                                                               \
  X(fmi3GetUInt8)                                                                              \
  X(fmi3GetInt16)                                                                              \
  X(fmi3GetUInt16)                                                                             \
  X(fmi3GetInt32)                                                                              \
  X(fmi3GetUInt32)                                                                             \
  X(fmi3GetInt64)                                                                              \
  X(fmi3GetUInt64)                                                                             \
  X(fmi3GetBoolean)                                                                            \
  X(fmi3GetString)                                                                             \
  X(fmi3GetBinary)                                                                             \
  X(fmi3GetClock)                                                                              \
  X(fmi3SetFloat32)                                                                            \
  X(fmi3SetFloat64)                                                                            \
  X(fmi3SetInt8)                                                                               \
  X(fmi3SetUInt8)                                                                              \
  X(fmi3SetInt16)                                                                              \
  X(fmi3SetUInt16)                                                                             \
  X(fmi3SetInt32)                                                                              \
  X(fmi3SetUInt32)                                                                             \
  X(fmi3SetInt64)                                                                              \
  X(fmi3SetUInt64)                                                                             \
  X(fmi3SetBoolean)                                                                            \
  X(fmi3SetString)                                                                             \
  X(fmi3SetBinary)                                                                             \
  X(fmi3SetClock)                                                                              \
  X(fmi3GetNumberOfVariableDependencies)                                                       \
  X(fmi3GetVariableDependencies)                                                               \
  X(fmi3GetFMUState)                                                                           \
  X(fmi3SetFMUState)                                                                           \
  X(fmi3FreeFMUState)                                                                          \
  X(fmi3SerializedFMUStateSize)                                                                \
  X(fmi3SerializeFMUState)                                                                     \
  X(fmi3DeserializeFMUState)                                                                   \
  X(fmi3GetDirectionalDerivative)                                                              \
  X(fmi3GetAdjointDerivative)                                                                  \
  X(fmi3EnterConfigurationMode)                                                                \
  X(fmi3ExitConfigurationMode)                                                                 \
  X(fmi3GetIntervalDecimal)                                                                    \
  X(fmi3GetIntervalFraction)                                                                   \
  X(fmi3GetShiftDecimal)                                                                       \
  X(fmi3GetShiftFraction)                                                                      \
  X(fmi3SetIntervalDecimal)                                                                    \
  X(fmi3SetIntervalFraction)                                                                   \
  X(fmi3SetShiftDecimal)                                                                       \
  X(fmi3SetShiftFraction)                                                                      \
  X(fmi3EvaluateDiscreteStates)                                                                \
  X(fmi3UpdateDiscreteStates)                                                                  \
  X(fmi3EnterContinuousTimeMode)                                                               \
  X(fmi3CompletedIntegratorStep)                                                               \
  X(fmi3SetTime)                                                                               \
  X(fmi3SetContinuousStates)                                                                   \
  X(fmi3GetContinuousStateDerivatives)                                                         \
  X(fmi3GetEventIndicators)                                                                    \
  X(fmi3GetContinuousStates)                                                                   \
  X(fmi3GetNominalsOfContinuousStates)                                                         \
  X(fmi3GetNumberOfEventIndicators)                                                            \
  X(fmi3GetNumberOfContinuousStates)                                                           \
  X(fmi3EnterStepMode)                                                                         \
  X(fmi3GetOutputDerivatives)                                                                  \
  X(fmi3DoStep)                                                                                \
  X(fmi3ActivateModelPartition)

#define FB_FMI3_FUNCTION_COUNT 75

/* Each function declared with its own type: a definition in the FMU
 * with any other signature does not compile. */
FB_FMI3_EXPORT fmi3GetVersionTYPE fmi3GetVersion;
FB_FMI3_EXPORT fmi3SetDebugLoggingTYPE fmi3SetDebugLogging;
FB_FMI3_EXPORT fmi3InstantiateModelExchangeTYPE fmi3InstantiateModelExchange;
FB_FMI3_EXPORT fmi3InstantiateCoSimulationTYPE fmi3InstantiateCoSimulation;
FB_FMI3_EXPORT fmi3InstantiateScheduledExecutionTYPE fmi3InstantiateScheduledExecution;
FB_FMI3_EXPORT fmi3FreeInstanceTYPE fmi3FreeInstance;
FB_FMI3_EXPORT fmi3EnterInitializationModeTYPE fmi3EnterInitializationMode;
FB_FMI3_EXPORT fmi3ExitInitializationModeTYPE fmi3ExitInitializationMode;
FB_FMI3_EXPORT fmi3EnterEventModeTYPE fmi3EnterEventMode;
FB_FMI3_EXPORT fmi3TerminateTYPE fmi3Terminate;
FB_FMI3_EXPORT fmi3ResetTYPE fmi3Reset;
FB_FMI3_EXPORT fmi3GetFloat32TYPE fmi3GetFloat32;
FB_FMI3_EXPORT fmi3GetFloat64TYPE fmi3GetFloat64;
FB_FMI3_EXPORT fmi3GetInt8TYPE fmi3GetInt8;
FB_FMI3_EXPORT fmi3GetUInt8TYPE fmi3GetUInt8;
FB_FMI3_EXPORT fmi3GetInt16TYPE fmi3GetInt16;
FB_FMI3_EXPORT fmi3GetUInt16TYPE fmi3GetUInt16;
FB_FMI3_EXPORT fmi3GetInt32TYPE fmi3GetInt32;
FB_FMI3_EXPORT fmi3GetUInt32TYPE fmi3GetUInt32;
FB_FMI3_EXPORT fmi3GetInt64TYPE fmi3GetInt64;
FB_FMI3_EXPORT fmi3GetUInt64TYPE fmi3GetUInt64;
FB_FMI3_EXPORT fmi3GetBooleanTYPE fmi3GetBoolean;
FB_FMI3_EXPORT fmi3GetStringTYPE fmi3GetString;
FB_FMI3_EXPORT fmi3GetBinaryTYPE fmi3GetBinary;
FB_FMI3_EXPORT fmi3GetClockTYPE fmi3GetClock;
FB_FMI3_EXPORT fmi3SetFloat32TYPE fmi3SetFloat32;
FB_FMI3_EXPORT fmi3SetFloat64TYPE fmi3SetFloat64;
FB_FMI3_EXPORT fmi3SetInt8TYPE fmi3SetInt8;
FB_FMI3_EXPORT fmi3SetUInt8TYPE fmi3SetUInt8;
FB_FMI3_EXPORT fmi3SetInt16TYPE fmi3SetInt16;
FB_FMI3_EXPORT fmi3SetUInt16TYPE fmi3SetUInt16;
FB_FMI3_EXPORT fmi3SetInt32TYPE fmi3SetInt32;
FB_FMI3_EXPORT fmi3SetUInt32TYPE fmi3SetUInt32;
FB_FMI3_EXPORT fmi3SetInt64TYPE fmi3SetInt64;
FB_FMI3_EXPORT fmi3SetUInt64TYPE fmi3SetUInt64;
FB_FMI3_EXPORT fmi3SetBooleanTYPE fmi3SetBoolean;
FB_FMI3_EXPORT fmi3SetStringTYPE fmi3SetString;
FB_FMI3_EXPORT fmi3SetBinaryTYPE fmi3SetBinary;
FB_FMI3_EXPORT fmi3SetClockTYPE fmi3SetClock;
FB_FMI3_EXPORT fmi3GetNumberOfVariableDependenciesTYPE fmi3GetNumberOfVariableDependencies;
FB_FMI3_EXPORT fmi3GetVariableDependenciesTYPE fmi3GetVariableDependencies;
FB_FMI3_EXPORT fmi3GetFMUStateTYPE fmi3GetFMUState;
FB_FMI3_EXPORT fmi3SetFMUStateTYPE fmi3SetFMUState;
FB_FMI3_EXPORT fmi3FreeFMUStateTYPE fmi3FreeFMUState;
FB_FMI3_EXPORT fmi3SerializedFMUStateSizeTYPE fmi3SerializedFMUStateSize;
FB_FMI3_EXPORT fmi3SerializeFMUStateTYPE fmi3SerializeFMUState;
FB_FMI3_EXPORT fmi3DeserializeFMUStateTYPE fmi3DeserializeFMUState;
FB_FMI3_EXPORT fmi3GetDirectionalDerivativeTYPE fmi3GetDirectionalDerivative;
FB_FMI3_EXPORT fmi3GetAdjointDerivativeTYPE fmi3GetAdjointDerivative;
FB_FMI3_EXPORT fmi3EnterConfigurationModeTYPE fmi3EnterConfigurationMode;
FB_FMI3_EXPORT fmi3ExitConfigurationModeTYPE fmi3ExitConfigurationMode;
FB_FMI3_EXPORT fmi3GetIntervalDecimalTYPE fmi3GetIntervalDecimal;
FB_FMI3_EXPORT fmi3GetIntervalFractionTYPE fmi3GetIntervalFraction;
FB_FMI3_EXPORT fmi3GetShiftDecimalTYPE fmi3GetShiftDecimal;
FB_FMI3_EXPORT fmi3GetShiftFractionTYPE fmi3GetShiftFraction;
FB_FMI3_EXPORT fmi3SetIntervalDecimalTYPE fmi3SetIntervalDecimal;
FB_FMI3_EXPORT fmi3SetIntervalFractionTYPE fmi3SetIntervalFraction;
FB_FMI3_EXPORT fmi3SetShiftDecimalTYPE fmi3SetShiftDecimal;
FB_FMI3_EXPORT fmi3SetShiftFractionTYPE fmi3SetShiftFraction;
FB_FMI3_EXPORT fmi3EvaluateDiscreteStatesTYPE fmi3EvaluateDiscreteStates;
FB_FMI3_EXPORT fmi3UpdateDiscreteStatesTYPE fmi3UpdateDiscreteStates;
FB_FMI3_EXPORT fmi3EnterContinuousTimeModeTYPE fmi3EnterContinuousTimeMode;
FB_FMI3_EXPORT fmi3CompletedIntegratorStepTYPE fmi3CompletedIntegratorStep;
FB_FMI3_EXPORT fmi3SetTimeTYPE fmi3SetTime;
FB_FMI3_EXPORT fmi3SetContinuousStatesTYPE fmi3SetContinuousStates;
FB_FMI3_EXPORT fmi3GetContinuousStateDerivativesTYPE fmi3GetContinuousStateDerivatives;
FB_FMI3_EXPORT fmi3GetEventIndicatorsTYPE fmi3GetEventIndicators;
FB_FMI3_EXPORT fmi3GetContinuousStatesTYPE fmi3GetContinuousStates;
FB_FMI3_EXPORT fmi3GetNominalsOfContinuousStatesTYPE fmi3GetNominalsOfContinuousStates;
FB_FMI3_EXPORT fmi3GetNumberOfEventIndicatorsTYPE fmi3GetNumberOfEventIndicators;
FB_FMI3_EXPORT fmi3GetNumberOfContinuousStatesTYPE fmi3GetNumberOfContinuousStates;
FB_FMI3_EXPORT fmi3EnterStepModeTYPE fmi3EnterStepMode;
FB_FMI3_EXPORT fmi3GetOutputDerivativesTYPE fmi3GetOutputDerivatives;
FB_FMI3_EXPORT fmi3DoStepTYPE fmi3DoStep;
FB_FMI3_EXPORT fmi3ActivateModelPartitionTYPE fmi3ActivateModelPartition;

#ifdef __cplusplus
}
#endif

#endif
