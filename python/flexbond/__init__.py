# SPDX-License-Identifier: BSD-3-Clause
"""flexbond from Python: scenarios, simulations, modes, frequency responses
and the exported linear model, over the shared library libflexbond (ctypes).

    import flexbond
    s = flexbond.Scenario("examples/apc6x6.yaml", overrides={"speed_kmh": 40})
    r = s.run("rigid")                # a Result: r.time, r["heave_acc"], r.units
    modes = s.modes("flexible")       # [Mode(freq_hz, damping_ratio, ...), ...]
    fr = s.freq_response("rigid", numpy.logspace(-1, 2, 200))
    m = s.export("rigid")             # E, A, B, f, C, D as scipy.sparse matrices

Every failure of the library raises flexbond.Error, which carries the
structured error (file, line, column, key) as attributes. docs/python.md
documents the whole interface.
"""

import collections
import concurrent.futures
import contextlib
import ctypes
import ctypes.util
import json
import math
import os
import re
import threading
import warnings

import numpy

__all__ = ["Scenario", "Simulation", "Result", "Corner", "Mode", "Modes", "FreqResponse",
           "RidePSD", "PsdRoad", "Model", "ModelFile", "Study", "HullMesh", "HullStressPeaks",
           "RunSummary",
           "Differences", "Sweep", "Error", "PlausibilityWarning", "RIGID", "FLEXIBLE",
           "NOTABLE_DIFF", "NOTABLE_CHANGE", "library_path"]

RIGID = 1      # System 1: rigid hull (fb_system FB_SYSTEM_RIGID)
FLEXIBLE = 2   # System 2: finite-element hull (FB_SYSTEM_FLEXIBLE)
_SYSTEMS = {"rigid": RIGID, "system1": RIGID, 1: RIGID,
            "flexible": FLEXIBLE, "system2": FLEXIBLE, 2: FLEXIBLE}
_SYSTEM_NAMES = {RIGID: "rigid", FLEXIBLE: "flexible"}
_SYSTEM_LABELS = {RIGID: "System 1 (rigid hull)", FLEXIBLE: "System 2 (flexible hull)"}
_FB_EINVAL = 2
_FB_EINTR = 8
_NTRACKS = 2  # FB_ROAD_NTRACKS: left, right
_FREQ_MAX_POINTS = 100000  # FB_STUDY_FREQ_MAX_POINTS
TRACKS = ("left", "right")


# ---- The C structures the interface passes (flexbond/error.h, vehicle.h, bd.h).

# fb_part_kind (flexbond/vehicle.h), by value; FB_ERR_NO_ELEMENT.
_PART_KINDS = (None, "vehicle", "corner", "mount", "point_mass", "section", "output",
               "load_point", "road", "tire", "hull_source", "damper", "spring", "stop",
               "body", "bushing", "antiroll_bar", "bogie", "envelope")
_NO_ELEMENT = ctypes.c_size_t(-1).value


class _ErrPart(ctypes.Structure):
    _fields_ = [("kind", ctypes.c_int), ("index", ctypes.c_size_t),
                ("element", ctypes.c_size_t), ("field", ctypes.c_char * 64)]


class _Err(ctypes.Structure):
    _fields_ = [("code", ctypes.c_int), ("msg", ctypes.c_char * 4096),
                ("origin", ctypes.c_int), ("origin_index", ctypes.c_size_t),
                ("key", ctypes.c_char * 256), ("file", ctypes.c_char * 1024),
                ("line", ctypes.c_int), ("column", ctypes.c_int),
                ("source", ctypes.c_int), ("source_text", ctypes.c_char * 512),
                ("excerpt", ctypes.c_char * 72), ("part", _ErrPart),
                ("text_start", ctypes.c_size_t)]


class _Mode(ctypes.Structure):
    _fields_ = [("re", ctypes.c_double), ("im", ctypes.c_double),
                ("freq_hz", ctypes.c_double), ("damping_ratio", ctypes.c_double),
                ("description", ctypes.c_char * 96)]


class _OutputStats(ctypes.Structure):
    _fields_ = [(n, ctypes.c_double) for n in
                ("static", "peak", "peak_time", "min", "min_time", "rms")]


class _OutputCmp(ctypes.Structure):
    _fields_ = [(n, ctypes.c_double) for n in
                ("max_diff", "max_diff_time", "range1", "rel_diff", "peak_change",
                 "rms_change")]


class _SimStats(ctypes.Structure):
    """fb_sim_stats (flexbond/sim.h)."""
    _fields_ = [(n, ctypes.c_long) for n in
                ("steps", "rhs_evals", "newton_setups", "factorizations", "newton_iters",
                 "newton_conv_fails", "err_test_fails", "events")] + [
                    ("last_order", ctypes.c_int), ("wall_seconds", ctypes.c_double)]


class _StudyRun(ctypes.Structure):
    """fb_study_run (flexbond/study.h): a run handed to a report, borrowed."""
    _fields_ = [("sys", ctypes.c_int), ("res", ctypes.c_void_p), ("sum", ctypes.c_void_p),
                ("basis_error", ctypes.POINTER(ctypes.c_double))]


class _HullMassProps(ctypes.Structure):
    _fields_ = [("mass", ctypes.c_double), ("cg", ctypes.c_double * 3),
                ("inertia", ctypes.c_double * 9)]


class _SectionTotals(ctypes.Structure):
    _fields_ = [("nelements", ctypes.c_size_t), ("area", ctypes.c_double),
                ("mass", ctypes.c_double)]


class _BdEigen(ctypes.Structure):
    """fb_bd_eigen (flexbond/bd.h)."""
    _fields_ = [("nstates", ctypes.c_size_t), ("n", ctypes.c_size_t),
                ("re", ctypes.POINTER(ctypes.c_double)), ("im", ctypes.POINTER(ctypes.c_double)),
                ("zero_tol", ctypes.c_double)]


class _Differences(ctypes.Structure):
    _fields_ = [(n, ctypes.c_size_t) for n in ("largest", "nvarying", "nnotable")]


class _ContactLoss(ctypes.Structure):
    _fields_ = [("corner", ctypes.c_int), ("t_start", ctypes.c_double),
                ("t_end", ctypes.c_double), ("min_force", ctypes.c_double),
                ("t_min", ctypes.c_double)]


class _RideMetrics(ctypes.Structure):
    _fields_ = [(n, ctypes.c_double) for n in
                ("a_w_rms", "mtvv", "vdv", "crest", "absorbed_power", "jerk_peak",
                 "jerk_rms", "duration", "nrmm_peak", "se", "dz", "vdv_ratio",
                 "crest_over_9")]


class _ModeSet(ctypes.Structure):
    _fields_ = [("nmodes", ctypes.c_size_t), ("ndof", ctypes.c_size_t),
                ("nfree", ctypes.c_size_t), ("nsolved", ctypes.c_size_t),
                ("freq_hz", ctypes.POINTER(ctypes.c_double)),
                ("shapes", ctypes.POINTER(ctypes.c_double)),
                ("description", ctypes.POINTER(ctypes.c_char * 96))]


class _Override(ctypes.Structure):
    _fields_ = [("key", ctypes.c_char_p), ("value", ctypes.c_char_p),
                ("label", ctypes.c_char_p)]


class _FmuOpts(ctypes.Structure):
    """fb_fmu_export_opts (flexbond/fmu.h)."""
    _fields_ = [("system", ctypes.c_int), ("road_inputs", ctypes.c_int),
                ("parameters", ctypes.POINTER(ctypes.c_char_p)),
                ("nparameters", ctypes.c_size_t),
                ("overrides", ctypes.POINTER(_Override)), ("noverrides", ctypes.c_size_t),
                ("t_end", ctypes.c_double), ("model_identifier", ctypes.c_char_p),
                ("runtime", ctypes.c_char_p),
                ("progress_fn", ctypes.c_void_p), ("progress_ctx", ctypes.c_void_p)]


class _FmuInfo(ctypes.Structure):
    """fb_fmu_info (flexbond/fmu.h)."""
    _fields_ = [("model_identifier", ctypes.c_char * 128)] + [
        (n, ctypes.c_size_t) for n in ("nstates", "ninputs", "noutputs", "nparameters",
                                       "nindicators", "nlibraries", "bytes")]


class _Descriptor(ctypes.Structure):
    _fields_ = [("n", ctypes.c_size_t), ("nstates", ctypes.c_size_t),
                ("ninputs", ctypes.c_size_t), ("noutputs", ctypes.c_size_t),
                ("nrows_c", ctypes.c_size_t),
                ("E", ctypes.c_void_p), ("A", ctypes.c_void_p), ("B", ctypes.c_void_p),
                ("f", ctypes.c_void_p), ("C", ctypes.c_void_p), ("D", ctypes.c_void_p),
                ("var_names", ctypes.POINTER(ctypes.c_char_p)),
                ("input_names", ctypes.POINTER(ctypes.c_char_p)),
                ("input_var", ctypes.POINTER(ctypes.c_size_t)),
                ("output_row", ctypes.POINTER(ctypes.c_size_t)),
                ("output_is_product", ctypes.POINTER(ctypes.c_int)),
                ("linearised", ctypes.c_int)]


_PROGRESS = ctypes.CFUNCTYPE(ctypes.c_int, ctypes.c_void_p, ctypes.c_double, ctypes.c_double)
# fb_progress_fn: (ctx, stage, fraction) -> nonzero to stop.
_STAGE_PROGRESS = ctypes.CFUNCTYPE(ctypes.c_int, ctypes.c_void_p, ctypes.c_char_p,
                                   ctypes.c_double)


class _Iso8608(ctypes.Structure):
    """fb_road_iso8608_params (flexbond/road.h)."""
    _fields_ = [("road_class", ctypes.c_char), ("seed", ctypes.c_uint64),
                ("n_min", ctypes.c_double), ("n_max", ctypes.c_double),
                ("nharmonics", ctypes.c_size_t), ("fade_length", ctypes.c_double),
                ("gd0", ctypes.c_double)]


class _PsdRoad(ctypes.Structure):
    """fb_study_psd_road (flexbond/study.h)."""
    _fields_ = [("road_class", ctypes.c_char), ("gd0", ctypes.c_double),
                ("n_min", ctypes.c_double), ("n_max", ctypes.c_double),
                ("speed", ctypes.c_double), ("identical", ctypes.c_int)]


_SWEEP_FINISHED = ctypes.CFUNCTYPE(ctypes.c_int, ctypes.c_void_p, ctypes.c_size_t,
                                   ctypes.POINTER(_Err))


class _SweepAxis(ctypes.Structure):
    """fb_study_sweep_axis (flexbond/study.h)."""
    _fields_ = [("key", ctypes.c_char_p), ("values", ctypes.POINTER(ctypes.c_char_p)),
                ("nvalues", ctypes.c_size_t)]


class _SweepOps(ctypes.Structure):
    """fb_study_sweep_ops: load, locate and stop are the library's own
    (fb_scenario_sweep_ops), never called from Python; measure is not used."""
    _fields_ = [("load", ctypes.c_void_p), ("locate", ctypes.c_void_p),
                ("stop", ctypes.c_void_p), ("finished", _SWEEP_FINISHED),
                ("ctx", ctypes.c_void_p), ("measure", ctypes.c_void_p)]


class _RideLimitOpts(ctypes.Structure):
    """fb_study_ride_limit_opts (flexbond/study.h)."""
    _fields_ = [("limit", ctypes.c_double), ("v_lo", ctypes.c_double),
                ("v_hi", ctypes.c_double), ("coarse_step", ctypes.c_double),
                ("tol", ctypes.c_double), ("refine_points", ctypes.c_size_t)]


class _RideLimitPoint(ctypes.Structure):
    """fb_study_ride_limit_point."""
    _fields_ = [("curve", ctypes.c_size_t), ("speed", ctypes.c_double)]


class _RideLimitCurve(ctypes.Structure):
    """fb_study_ride_limit_curve."""
    _fields_ = [("status", ctypes.c_int), ("speed", ctypes.c_double),
                ("metric", ctypes.c_double), ("speed_over", ctypes.c_double),
                ("metric_over", ctypes.c_double), ("failed_speed", ctypes.c_double),
                ("nruns", ctypes.c_size_t)]


_RIDE_LIMIT_EVAL = ctypes.CFUNCTYPE(ctypes.c_int, ctypes.c_void_p,
                                    ctypes.POINTER(_RideLimitPoint), ctypes.c_size_t,
                                    ctypes.POINTER(ctypes.c_double), ctypes.POINTER(_Err))


class _SweepSource(ctypes.Structure):
    """fb_scenario_sweep_source (flexbond/io.h)."""
    _fields_ = [("path", ctypes.c_char_p), ("text", ctypes.c_char_p), ("len", ctypes.c_size_t),
                ("display_name", ctypes.c_char_p), ("overrides", ctypes.POINTER(_Override)),
                ("noverrides", ctypes.c_size_t), ("axes_name", ctypes.c_char_p)]


class _SweepCase(ctypes.Structure):
    """fb_study_sweep_case (flexbond/study.h)."""
    _fields_ = [("status", ctypes.c_int), ("at_value", ctypes.c_int),
                ("error", ctypes.c_char_p), ("metric", ctypes.POINTER(ctypes.c_double)),
                ("wall_seconds", ctypes.c_double), ("worker", ctypes.c_int)]


class _HullStressPeaks(ctypes.Structure):
    # fb_hull_stress_peaks (flexbond/hull_stress.h); fb_hull_surface is an int.
    _fields_ = [("nelements", ctypes.c_size_t), ("nsamples", ctypes.c_size_t),
                ("von_mises", ctypes.POINTER(ctypes.c_double)),
                ("time", ctypes.POINTER(ctypes.c_double)),
                ("surface", ctypes.POINTER(ctypes.c_int)),
                ("range", ctypes.POINTER(ctypes.c_double)),
                ("range_surface", ctypes.POINTER(ctypes.c_int))]


class _VehicleOpts(ctypes.Structure):
    """fb_vehicle_opts (flexbond/vehicle.h), filled by fb_vehicle_opts_default."""
    _fields_ = [("motion", ctypes.c_int), ("memory_limit", ctypes.c_size_t),
                ("progress_fn", _STAGE_PROGRESS), ("progress_ctx", ctypes.c_void_p),
                ("threads", ctypes.c_int), ("hull_modes", ctypes.c_size_t),
                ("road_inputs", ctypes.c_int)]
class _SimOpts(ctypes.Structure):
    """fb_sim_opts (flexbond/sim.h), filled by fb_model_sim_opts_with."""
    _fields_ = [(n, ctypes.c_double) for n in
                ("t_start", "t_end", "rtol", "atol", "max_step", "sample_rate")] + [
                    ("max_order", ctypes.c_int), ("max_steps", ctypes.c_long),
                    ("stability_limit_detection", ctypes.c_int),
                    ("breakpoints", ctypes.POINTER(ctypes.c_double)),
                    ("nbreakpoints", ctypes.c_size_t), ("x0", ctypes.POINTER(ctypes.c_double)),
                    ("progress", _PROGRESS), ("progress_ctx", ctypes.c_void_p),
                    ("noutputs", ctypes.c_size_t)]


_P = ctypes.c_void_p
_PP = ctypes.POINTER(ctypes.c_void_p)
_PERR = ctypes.POINTER(_Err)
_PSIZE = ctypes.POINTER(ctypes.c_size_t)
_PDOUBLE = ctypes.POINTER(ctypes.c_double)

# name: (result type, argument types)
_PROTOTYPES = {
    "fb_status_name": (ctypes.c_char_p, [ctypes.c_int]),
    "fb_scenario_load_overrides": (ctypes.c_int, [ctypes.c_char_p, ctypes.POINTER(_Override),
                                                  ctypes.c_size_t, _PP, _PERR]),
    "fb_scenario_free": (None, [_PP]),
    "fb_scenario_load_string": (ctypes.c_int, [ctypes.c_char_p, ctypes.c_size_t, ctypes.c_char_p,
                                               _PP, _PERR]),
    "fb_scenario_locate": (ctypes.c_int, [_P, _PERR]),
    "fb_scenario_nwarnings": (ctypes.c_size_t, [_P]),
    "fb_scenario_warning": (_PERR, [_P, ctypes.c_size_t]),
    "fb_scenario_noutputs": (ctypes.c_size_t, [_P]),
    "fb_scenario_output_name": (ctypes.c_char_p, [_P, ctypes.c_size_t]),
    "fb_scenario_output_unit": (ctypes.c_char_p, [_P, ctypes.c_size_t]),
    "fb_scenario_ncorners": (ctypes.c_size_t, [_P]),
    "fb_scenario_corner_name": (ctypes.c_char_p, [_P, ctypes.c_size_t]),
    "fb_scenario_corner_position": (None, [_P, ctypes.c_size_t, _PDOUBLE, _PDOUBLE]),
    "fb_scenario_speed": (ctypes.c_double, [_P]),
    "fb_scenario_frame_offset": (None, [_P, ctypes.POINTER(ctypes.c_double * 3)]),
    "fb_vehicle_opts_default": (None, [ctypes.POINTER(_VehicleOpts)]),
    "fb_vehicle_new": (ctypes.c_int, [_P, ctypes.c_int, ctypes.POINTER(_VehicleOpts), _PP,
                                      _PERR]),
    "fb_vehicle_free": (None, [_PP]),
    "fb_vehicle_run": (ctypes.c_int, [_P, _PDOUBLE, _PROGRESS, _P, _PP, _P, _PERR]),
    "fb_vehicle_hull_free_modes": (ctypes.c_size_t, [_P, ctypes.POINTER(_PDOUBLE),
                                                      ctypes.POINTER(ctypes.c_size_t)]),
    "fb_vehicle_structural_modes": (ctypes.c_int, [_P, ctypes.c_size_t, ctypes.c_int,
                                                   ctypes.POINTER(ctypes.POINTER(_ModeSet)),
                                                   _PERR]),
    "fb_mode_set_free": (None, [ctypes.POINTER(ctypes.POINTER(_ModeSet))]),
    "fb_run_summary_new": (ctypes.c_int, [_P, _P, _PDOUBLE, _PP, _PERR]),
    "fb_run_summary_free": (None, [_PP]),
    "fb_run_summary_window": (None, [_P, _PDOUBLE]),
    "fb_run_summary_output": (ctypes.POINTER(_OutputStats), [_P, ctypes.c_size_t]),
    "fb_run_summary_contact": (ctypes.POINTER(_OutputStats), [_P, ctypes.c_size_t]),
    "fb_run_summary_contact_ratio": (ctypes.c_double, [_P, ctypes.c_size_t]),
    "fb_run_summary_contact_spike": (ctypes.c_int, [_P, ctypes.c_size_t]),
    "fb_run_summary_nlosses": (ctypes.c_size_t, [_P]),
    "fb_run_summary_loss": (ctypes.POINTER(_ContactLoss), [_P, ctypes.c_size_t]),
    "fb_run_summary_ride": (ctypes.c_int, [_P, ctypes.POINTER(_RideMetrics), _PDOUBLE,
                                           ctypes.POINTER(ctypes.c_char_p)]),
    "fb_study_compare": (ctypes.c_int, [_P, _P, _P, _P, _P, ctypes.POINTER(_OutputCmp), _PP,
                                        _PERR]),
    "fb_scenario_sweep_ops": (None, [ctypes.POINTER(_SweepSource), ctypes.POINTER(_SweepOps)]),
    "fb_study_sweep_new": (ctypes.c_int, [_P, ctypes.c_int, ctypes.POINTER(_SweepAxis),
                                          ctypes.c_size_t, ctypes.POINTER(_SweepOps), _PP,
                                          _PERR]),
    "fb_study_sweep_free": (None, [_PP]),
    "fb_study_sweep_ncases": (ctypes.c_size_t, [_P]),
    "fb_study_sweep_nmetrics": (ctypes.c_size_t, [_P]),
    "fb_study_sweep_case_value": (ctypes.c_char_p, [_P, ctypes.c_size_t, ctypes.c_size_t]),
    "fb_study_sweep_metric_name": (None, [_P, ctypes.c_size_t, ctypes.c_char_p,
                                          ctypes.c_size_t]),
    "fb_study_sweep_metric_unit": (ctypes.c_char_p, [_P, ctypes.c_size_t]),
    "fb_study_sweep_case_get": (ctypes.c_int, [_P, ctypes.c_size_t,
                                               ctypes.POINTER(_SweepCase)]),
    "fb_study_sweep_run": (ctypes.c_int, [_P, ctypes.c_size_t, _PERR]),
    "fb_study_sweep_cancel": (None, [_P]),
    "fb_study_ride_limit_opts_default": (None, [ctypes.POINTER(_RideLimitOpts)]),
    "fb_study_ride_limit": (ctypes.c_int, [ctypes.c_size_t, ctypes.POINTER(_RideLimitOpts),
                                           _RIDE_LIMIT_EVAL, _P,
                                           ctypes.POINTER(_RideLimitCurve), _PSIZE, _PERR]),
    "fb_study_ride_limit_metric_find": (ctypes.c_int, [ctypes.c_char_p, _PSIZE]),
    "fb_study_ride_limit_metric_limit": (ctypes.c_double, [ctypes.c_size_t]),
    "fb_study_ride_limit_duration": (ctypes.c_int, [_P, ctypes.c_double, ctypes.c_double,
                                                    _PERR]),
    "fb_study_ride_limit_measure": (ctypes.c_int, [_P, _P, ctypes.c_size_t, ctypes.c_size_t,
                                                   _PDOUBLE, _PERR]),
    "fb_study_ride_output": (ctypes.c_size_t, [_P]),
    "fb_vehicle_simulate": (ctypes.c_int, [_P, ctypes.c_int, _PP, _PERR]),
    "fb_study_mesh_error": (ctypes.c_int, [_P, _PDOUBLE]),
    "fb_study_response_window": (None, [_P, _PDOUBLE]),
    "fb_vehicle_basis_reduced": (ctypes.c_int, [_P]),
    "fb_scenario_converged_density": (ctypes.c_int, [_P]),
    "fb_scenario_use_auto_basis": (None, [_P]),
    "fb_study_report_mesh_crossings": (ctypes.c_size_t, [_P]),
    "fb_study_report_mesh_diff": (ctypes.c_double, [_P, ctypes.c_size_t]),
    "fb_vehicle_basis_error": (ctypes.c_int, [_P, _P, _PDOUBLE, _PROGRESS, _P, _PDOUBLE, _PERR]),
    "fb_study_report_new": (ctypes.c_int, [_P, ctypes.POINTER(_StudyRun), ctypes.c_size_t,
                                           ctypes.POINTER(_StudyRun), _PP, _PERR]),
    "fb_study_report_free": (None, [_PP]),
    "fb_study_report_window": (None, [_P, _PDOUBLE]),
    "fb_study_report_wheel_window": (None, [_P, ctypes.c_size_t, _PDOUBLE]),
    "fb_study_report_cmp": (ctypes.POINTER(_OutputCmp), [_P, ctypes.c_int]),
    "fb_study_report_differences": (_Differences, [_P, ctypes.c_int]),
    "fb_study_report_notable": (ctypes.c_int, [_P, ctypes.c_int, ctypes.c_size_t]),
    "fb_study_report_largest_rms_change": (ctypes.c_size_t, [_P]),
    "fb_study_report_torsion_output": (ctypes.c_size_t, [_P]),
    "fb_study_report_run": (ctypes.POINTER(_StudyRun), [_P, ctypes.c_size_t]),
    "fb_study_run_max_abs": (ctypes.c_double, [ctypes.POINTER(_StudyRun), ctypes.c_size_t]),
    "fb_study_report_largest_growth": (ctypes.c_size_t, [_P, _PDOUBLE]),
    "fb_study_report_contact_extremes": (None, [_P, ctypes.POINTER(_StudyRun), _PSIZE, _PSIZE]),
    "fb_scenario_corner_tire": (ctypes.c_char_p, [_P, ctypes.c_size_t]),
    "fb_vehicle_fe_hull": (ctypes.c_int, [_P, _PP, _PERR]),
    "fb_fe_hull_free": (None, [_PP]),
    "fb_fe_hull_mesh": (_P, [_P]),
    "fb_fe_hull_npoint_masses": (ctypes.c_size_t, [_P]),
    "fb_fe_hull_mass_props": (ctypes.c_int, [_P, ctypes.c_int, ctypes.POINTER(_HullMassProps),
                                             _PERR]),
    "fb_fe_hull_matrices": (ctypes.c_int, [_P, _PP, _PP, _PERR]),
    "fb_fe_hull_section_totals": (_SectionTotals, [_P, ctypes.c_long]),
    "fb_mesh_nnodes": (ctypes.c_size_t, [_P]),
    "fb_mesh_count": (ctypes.c_size_t, [_P, ctypes.c_int]),
    "fb_mesh_nsections": (ctypes.c_size_t, [_P]),
    "fb_mesh_section_elset": (ctypes.c_char_p, [_P, ctypes.c_size_t]),
    "fb_mesh_nelements": (ctypes.c_size_t, [_P]),
    "fb_mesh_element_id": (ctypes.c_long, [_P, ctypes.c_size_t]),
    "fb_mesh_element_type": (ctypes.c_int, [_P, ctypes.c_size_t]),
    "fb_mesh_element_nodes": (ctypes.POINTER(ctypes.c_size_t), [_P, ctypes.c_size_t]),
    "fb_mesh_element_centroid": (None, [_P, ctypes.c_size_t, _PDOUBLE]),
    "fb_mesh_element_section": (ctypes.c_long, [_P, ctypes.c_size_t]),
    "fb_mesh_node_xyz": (_PDOUBLE, [_P, ctypes.c_size_t]),
    "fb_vehicle_motion_free": (None, [_PP]),
    "fb_hull_stress_new": (ctypes.c_int, [_P, _PP, _PERR]),
    "fb_hull_stress_free": (None, [_PP]),
    "fb_hull_stress_mesh": (_P, [_P]),
    "fb_hull_stress_peaks_of": (ctypes.c_int, [_P, _P, ctypes.c_double,
                                               ctypes.POINTER(ctypes.POINTER(_HullStressPeaks)),
                                               _PERR]),
    "fb_hull_stress_peaks_free": (None, [ctypes.POINTER(ctypes.POINTER(_HullStressPeaks))]),
    "fb_bd_build": (ctypes.c_int, [_P, _P, ctypes.c_size_t, _PP, _PERR]),
    "fb_bd_free": (None, [_PP]),
    "fb_bd_nstates": (ctypes.c_size_t, [_P]),
    "fb_bd_eigen_new": (ctypes.c_int, [_P, ctypes.c_double, _PDOUBLE, ctypes.c_size_t,
                                       ctypes.c_char_p, ctypes.POINTER(ctypes.POINTER(_BdEigen)),
                                       _PERR]),
    "fb_bd_eigen_free": (None, [ctypes.POINTER(ctypes.POINTER(_BdEigen))]),
    "fb_bg_free": (None, [_PP]),
    "fb_vehicle_graph": (ctypes.c_int, [_P, ctypes.c_int, _PP, _PP, _PSIZE, _PERR]),
    "fb_vehicle_probes_free": (None, [_PP, ctypes.c_size_t]),
    "fb_vehicle_sim_opts": (None, [_P, ctypes.POINTER(_SimOpts)]),
    "fb_model_graph": (_P, [_P]),
    "fb_model_sim_opts": (ctypes.POINTER(_SimOpts), [_P]),
    "fb_model_blame": (ctypes.c_int, [_P, _PERR]),
    "fb_model_load": (ctypes.c_int, [ctypes.c_char_p, _PP, _PERR]),
    "fb_model_free": (None, [_PP]),
    "fb_model_name": (ctypes.c_char_p, [_P]),
    "fb_model_nwarnings": (ctypes.c_size_t, [_P]),
    "fb_model_warning": (_PERR, [_P, ctypes.c_size_t]),
    "fb_model_sim_new": (ctypes.c_int, [_P, _PP, _PERR]),
    "fb_model_sim_free": (None, [_PP]),
    "fb_model_sim_opts_with": (_SimOpts, [_P, ctypes.c_double, ctypes.c_double,
                                          ctypes.c_double]),
    "fb_model_sim_run": (ctypes.c_int, [_P, ctypes.POINTER(_SimOpts), _PP, _PERR]),
    "fb_study_freq_log_grid": (None, [ctypes.c_double, ctypes.c_double, ctypes.c_size_t,
                                      _PDOUBLE]),
    "fb_study_freq_new": (ctypes.c_int, [_P, _PDOUBLE, ctypes.c_size_t, _PP, _PERR]),
    "fb_study_freq_free": (None, [_PP]),
    "fb_study_freq_nfreq": (ctypes.c_size_t, [_P]),
    "fb_study_freq_hz": (_PDOUBLE, [_P]),
    "fb_study_freq_linearised": (ctypes.c_int, [_P]),
    "fb_study_freq_has_output": (ctypes.c_int, [_P, ctypes.c_size_t]),
    "fb_study_freq_at": (_PDOUBLE, [_P, ctypes.c_size_t, ctypes.c_int, ctypes.c_size_t]),
    "fb_study_freq_peak": (ctypes.c_double, [_P, ctypes.c_size_t, _PSIZE,
                                             ctypes.POINTER(ctypes.c_int)]),
    "fb_study_ride_psd_iso8608": (ctypes.c_int, [_P, ctypes.c_char, ctypes.POINTER(_Iso8608)]),
    "fb_study_ride_psd_new": (ctypes.c_int, [_P, ctypes.POINTER(_Iso8608), ctypes.c_int, _PP,
                                             _PERR]),
    "fb_study_ride_psd_free": (None, [_PP]),
    "fb_study_ride_psd_road": (ctypes.POINTER(_PsdRoad), [_P]),
    "fb_study_ride_psd_linearised": (ctypes.c_int, [_P]),
    "fb_study_ride_psd_nfreq": (ctypes.c_size_t, [_P]),
    "fb_study_ride_psd_hz": (_PDOUBLE, [_P]),
    "fb_study_ride_psd_road_psd": (_PDOUBLE, [_P]),
    "fb_study_ride_psd_output": (_PDOUBLE, [_P, ctypes.c_size_t]),
    "fb_study_ride_psd_rms": (ctypes.c_double, [_P, ctypes.c_size_t]),
    "fb_study_ride_psd_a_w_output": (ctypes.c_size_t, [_P]),
    "fb_study_ride_psd_weighted": (_PDOUBLE, [_P]),
    "fb_study_ride_psd_a_w": (ctypes.c_double, [_P]),
    "fb_vehicle_linear_modes": (ctypes.c_int, [_P, ctypes.c_int,
                                               ctypes.POINTER(ctypes.POINTER(_Mode)), _PSIZE,
                                               _PSIZE, _PERR]),
    "fb_result_nsamples": (ctypes.c_size_t, [_P]),
    "fb_result_ncols": (ctypes.c_size_t, [_P]),
    "fb_result_col_name": (ctypes.c_char_p, [_P, ctypes.c_size_t]),
    "fb_result_col_unit": (ctypes.c_char_p, [_P, ctypes.c_size_t]),
    "fb_result_row": (_PDOUBLE, [_P, ctypes.c_size_t]),
    "fb_result_free": (None, [_PP]),
    "fb_result_stats": (ctypes.POINTER(_SimStats), [_P]),
    "fb_vehicle_linearise": (ctypes.c_int, [_P, ctypes.POINTER(ctypes.POINTER(_Descriptor)),
                                            _PERR]),
    "fb_descriptor_free": (None, [ctypes.POINTER(ctypes.POINTER(_Descriptor))]),
    "fb_vehicle_freq_response": (ctypes.c_int, [_P, ctypes.POINTER(_Descriptor), _PDOUBLE,
                                                ctypes.c_size_t, _PDOUBLE, _PERR]),
    "fb_vehicle_input_name": (ctypes.c_char_p, [ctypes.c_size_t]),
    "fb_vehicle_stepper_new": (ctypes.c_int, [_P, ctypes.c_int, ctypes.POINTER(_VehicleOpts),
                                              _PP, _PERR]),
    "fb_vehicle_stepper_free": (None, [_PP]),
    "fb_fmu_export": (ctypes.c_int, [ctypes.c_char_p, ctypes.POINTER(_FmuOpts), ctypes.c_char_p,
                                     ctypes.POINTER(_FmuInfo), _PERR]),
    "fb_vehicle_stepper_advance": (ctypes.c_int, [_P, ctypes.c_double, _PERR]),
    "fb_vehicle_stepper_time": (ctypes.c_double, [_P]),
    "fb_vehicle_stepper_noutputs": (ctypes.c_size_t, [_P]),
    "fb_vehicle_stepper_output_name": (ctypes.c_char_p, [_P, ctypes.c_size_t]),
    "fb_vehicle_stepper_output_unit": (ctypes.c_char_p, [_P, ctypes.c_size_t]),
    "fb_vehicle_stepper_outputs": (ctypes.c_int, [_P, _PDOUBLE, _PERR]),
    "fb_vehicle_stepper_set_input": (ctypes.c_int, [_P, ctypes.c_char_p, ctypes.c_double,
                                                    _PERR]),
    "fb_vehicle_stepper_input": (ctypes.c_double, [_P, ctypes.c_size_t]),
    "fb_vehicle_stepper_set_scenario": (ctypes.c_int, [_P, _P, _PERR]),
    "fb_mat_free": (None, [_PP]),
    "fb_mat_nrows": (ctypes.c_size_t, [_P]),
    "fb_mat_ncols": (ctypes.c_size_t, [_P]),
    "fb_mat_nnz": (ctypes.c_size_t, [_P]),
    "fb_mat_triplets": (ctypes.c_size_t, [_P, _PSIZE, _PSIZE, _PDOUBLE]),
}


def _find_library():
    """The shared library: $FLEXBOND_LIBRARY, else the path `cmake --install`
    wrote next to this file, else the loader's search (ldconfig)."""
    env = os.environ.get("FLEXBOND_LIBRARY")
    if env:
        return env
    try:
        with open(os.path.join(os.path.dirname(__file__), "library_path"), encoding="utf-8") as f:
            path = f.read().strip()
        if path:
            return path
    except FileNotFoundError:
        pass
    name = ctypes.util.find_library("flexbond")
    if name:
        return name
    raise ImportError("flexbond: libflexbond.so not found: install flexbond (make install) or "
                      "set FLEXBOND_LIBRARY to the library's path")


def _load():
    path = _find_library()
    lib = ctypes.CDLL(path)
    for name, (restype, argtypes) in _PROTOTYPES.items():
        fn = getattr(lib, name)
        fn.restype = restype
        fn.argtypes = argtypes
    libc = ctypes.CDLL(ctypes.util.find_library("c"))
    libc.free.restype = None
    libc.free.argtypes = [ctypes.c_void_p]
    return path, lib, libc


library_path, _lib, _libc = _load()


# ---- Errors.

class Error(Exception):
    """A failure of the library, with the structured error of flexbond/error.h:
    code (int) and status ("FB_EPARSE"), message, and where known the input
    value it is about: file, line and column (1-based, 0 unknown), key (its
    key path, "road.speed_kmh"), source_text (the override, for a value
    given in overrides), and excerpt: the one field of a data file (a table,
    a profile) that failed, which message never quotes; str(error) shows it.
    part: the part of the vehicle it is about, as the library names it
    (flexbond/vehicle.h, fb_part_kind), a tuple (kind, index, field, element)
    such as ("corner", 2, "spring_k", None), ("vehicle", 0, "hull_modes",
    None), ("tire", 2, "deflection_ref", None) (corner 2's tire model's
    parameter) or ("damper", 3, "c2", None) (corner 3's damper law's
    parameter); None when it is about no part. path: for a vehicle described by
    Python data (Scenario.from_dict), the value's place in it,
    "description['suspensions']['axles'][0]['spring_k']"; None otherwise."""

    def __init__(self, err):
        self.code = err.code
        self.status = _lib.fb_status_name(err.code).decode()
        self.message = err.msg.decode(errors="replace")
        self.file = err.file.decode(errors="replace") or None
        self.line = err.line
        self.column = err.column
        self.key = err.key.decode(errors="replace") or None
        self.source_text = err.source_text.decode(errors="replace") or None
        self.excerpt = err.excerpt.decode(errors="replace") or None
        self.path = None
        p = err.part
        self.part = None if not 0 < p.kind < len(_PART_KINDS) else (
            _PART_KINDS[p.kind], p.index, p.field.decode(errors="replace"),
            None if p.element == _NO_ELEMENT else p.element)
        super().__init__(self.message if self.excerpt is None
                         else f"{self.message} (read: '{self.excerpt}')")


class PlausibilityWarning(UserWarning):
    """A scenario value that is legal but implausible (flexbond's warning
    "FILE:LINE:COL: KEY: VALUE is implausible: WHY"); Scenario(...,
    strict=True) raises Error instead."""


def _check(rc, err):
    if rc != 0:
        raise Error(err)


def _key_path(name, key):
    """The Python path of a scenario key path in the data named name:
    "suspensions.axles[0].spring_k" -> name['suspensions']['axles'][0]['spring_k']."""
    parts = re.findall(r"([^.\[\]]+)|\[(\d+)\]", key)
    return name + "".join("[%d]" % int(i) if i else "[%r]" % k for k, i in parts)


def _in_data(error, err, name):
    """error (from err), about a value of the data named name: said at the
    value's path there, not at the line of the text it was read from."""
    error.path = _key_path(name, error.key) if error.key else name
    text = err.msg[err.text_start:].decode(errors="replace")
    error.message = "%s: %s" % (error.path, text)
    error.file, error.line, error.column = None, 0, 0
    error.args = (error.message if error.excerpt is None
                  else "%s (read: '%s')" % (error.message, error.excerpt),)
    return error


def _check_about(s, rc, err, data_name=None):
    """_check for a call on scenario s, whose error may be about one of its
    values (Error.part): located first where that value was written (the
    file's line and key, or the override as the caller wrote it; for a
    scenario made from data named data_name, the value's path there)."""
    if rc != 0:
        _lib.fb_scenario_locate(s, ctypes.byref(err))
        raise Error(err) if data_name is None else _in_data(Error(err), err, data_name)


def _c_text(text, what, key=None):
    """text as the NUL-terminated bytes C reads (a path through os.fsencode).
    A NUL inside would end it there, silently: "12\\x0099" read as 12, a
    path "s.yaml\\x00.x" as s.yaml, so such text raises Error instead."""
    b = os.fsencode(text) if what == "path" else str(text).encode()
    if b"\0" not in b:
        return b
    err = _Err()
    err.code = _FB_EINVAL
    err.msg = f"{what} {text!r}: holds a NUL character".encode()[:4000]
    if key is not None:
        err.key = str(key).encode(errors="replace").replace(b"\0", b"\\0")[:255]
    raise Error(err)


def _system(system):
    key = system.lower() if isinstance(system, str) else system
    if key not in _SYSTEMS:
        raise ValueError("flexbond: system %r: one of 'rigid' (1) or 'flexible' (2)" % (system,))
    return _SYSTEMS[key]


def _text(value):
    """An override's value as the file would write it: exact for floats."""
    if isinstance(value, bool):
        raise TypeError("flexbond: a boolean is no scenario value")
    if isinstance(value, float):
        return repr(float(value))  # numpy.float64's repr is "np.float64(...)" from NumPy 2
    return str(value)


# ---- Results.

class Result:
    """One system's simulation: data (nsamples x ncols), column 0 the time.
    names and units give each column's; r["name"] is a column. stats holds
    the solver's counts (summary.json's and stats.json's "solver": steps,
    rhs_evals, newton_setups, factorizations, newton_iters,
    newton_conv_fails, err_test_fails, events, last_order) and the
    integration's wall_seconds."""

    def __init__(self, system, names, units, data, stats=None):
        self.system = system
        self.names = names
        self.units = units
        self.data = data
        self.stats = stats or {}
        self._index = {n: j for j, n in enumerate(names)}

    @property
    def time(self):
        return self.data[:, 0]

    def __getitem__(self, name):
        try:
            return self.data[:, self._index[name]]
        except KeyError:
            raise KeyError("flexbond: no column %r; the columns are %s"
                           % (name, ", ".join(self.names))) from None

    def __contains__(self, name):
        return name in self._index

    def unit(self, name):
        return self.units[self._index[name]]

    def __len__(self):
        return self.data.shape[0]

    def __repr__(self):
        return "<flexbond.Result %s: %d samples of %d columns>" % (
            self.system, self.data.shape[0], self.data.shape[1])


def _result(res, system):
    nsamples = _lib.fb_result_nsamples(res)
    ncols = _lib.fb_result_ncols(res)
    names = [_lib.fb_result_col_name(res, j).decode() for j in range(ncols)]
    units = [_lib.fb_result_col_unit(res, j).decode() for j in range(ncols)]
    data = numpy.empty((nsamples, ncols))
    if nsamples:
        start = _lib.fb_result_row(res, 0)
        data[...] = numpy.ctypeslib.as_array(start, shape=(nsamples, ncols))
    stats = _lib.fb_result_stats(res).contents
    return Result(system, names, units, data,
                  {n: getattr(stats, n) for n, _ in _SimStats._fields_})


Corner = collections.namedtuple("Corner", "name x y")
# A ride-limit curve's point (Scenario.ride_limit): ride_limit.csv's row.
RideLimit = collections.namedtuple(
    "RideLimit", "value system status speed_kmh metric speed_over_kmh metric_over runs error")
_RIDE_LIMIT_STATUS = ("found", "below", "above", "failed")

OutputStats = collections.namedtuple("OutputStats", "static peak peak_time min min_time rms")
OutputStats.__doc__ = """One output over the response window (flexbond/study.h): static (the
last sample before it), peak and min from its start on with their first times,
rms over it; summary.json's "outputs"."""

ContactLoss = collections.namedtuple("ContactLoss", "tire start end min_force at")
ContactLoss.__doc__ = """A tire's interval of lost contact: from start to end (s), its
smallest reaction min_force (N, <= 0) at time at."""

OutputComparison = collections.namedtuple(
    "OutputComparison", "max_diff max_diff_time range1 rel_diff peak_change rms_change")
OutputComparison.__doc__ = """An output of the second system against the first, from the
window's start on: the largest |difference| and its time, the first system's
range, their ratio, and the relative changes of peak and rms (NaN where a
denominator is 0); summary.json's "comparison"."""


class RunSummary:
    """A run summarised by the library's study layer, as flexbond run writes
    it in summary.json: result (the Result), window (the response window, s),
    outputs {name: OutputStats}, contact {tire: OutputStats} of each tire's
    normal reaction, contact_ratio {tire: peak / static}, spikes (tires above
    flexbond's spike ratio), contact_loss [ContactLoss], and ride: the ride
    metrics {a_w_rms, mtvv, vdv, crest, absorbed_power, jerk_peak, jerk_rms,
    duration, nrmm_peak, se, dz, vdv_ratio, crest_over_9} of the first mounted
    body's acceleration over ride_window, or
    None with ride_note saying why; basis_error {output: estimated error of
    System 2's reduced modal basis, over the output's range} when
    Scenario.study estimated it, else None."""

    def __init__(self, scenario, system, res, summary, basis_error=None):
        self.system = system
        self.result = _result(res, system)
        window = (ctypes.c_double * 2)()
        _lib.fb_run_summary_window(summary, window)
        self.window = (window[0], window[1])
        names = [_lib.fb_scenario_output_name(scenario, k).decode()
                 for k in range(_lib.fb_scenario_noutputs(scenario))]
        tires = [_lib.fb_scenario_corner_name(scenario, c).decode()
                 for c in range(_lib.fb_scenario_ncorners(scenario))]
        self.outputs = {n: _stats(_lib.fb_run_summary_output(summary, k).contents)
                        for k, n in enumerate(names)}
        self.basis_error = (None if basis_error is None
                            else {n: basis_error[k] for k, n in enumerate(names)})
        self.contact = {n: _stats(_lib.fb_run_summary_contact(summary, c).contents)
                        for c, n in enumerate(tires)}
        self.contact_ratio = {n: _lib.fb_run_summary_contact_ratio(summary, c)
                              for c, n in enumerate(tires)}
        self.spikes = [n for c, n in enumerate(tires)
                       if _lib.fb_run_summary_contact_spike(summary, c)]
        self.contact_loss = []
        for i in range(_lib.fb_run_summary_nlosses(summary)):
            loss = _lib.fb_run_summary_loss(summary, i).contents
            self.contact_loss.append(ContactLoss(tires[loss.corner], loss.t_start, loss.t_end,
                                                 loss.min_force, loss.t_min))
        ride = _RideMetrics()
        note = ctypes.c_char_p()
        if _lib.fb_run_summary_ride(summary, ctypes.byref(ride), window, ctypes.byref(note)):
            self.ride = {n: getattr(ride, n) for n, _ in _RideMetrics._fields_}
            self.ride_window = (window[0], window[1])
            self.ride_note = None
        else:
            self.ride, self.ride_window = None, None
            self.ride_note = note.value.decode(errors="replace")


def _findings(s, rep, names):
    """Study's members from the report data rep of the runs of systems names."""
    outputs = [_lib.fb_scenario_output_name(s, k).decode()
               for k in range(_lib.fb_scenario_noutputs(s))]
    tires = [_lib.fb_scenario_corner_name(s, c).decode()
             for c in range(_lib.fb_scenario_ncorners(s))]

    def output(k):
        return outputs[k] if k < len(outputs) else None

    window = (ctypes.c_double * 2)()
    mesh_error = (tuple(window) if _lib.fb_study_mesh_error(s, window) else None)
    _lib.fb_study_report_window(rep, window)
    found = {"window": (window[0], window[1]), "mesh_error": mesh_error,
             "wheel_windows": {}, "comparison": None,
             "differences": None, "torsion_max_abs": {}, "contact_extremes": {}}
    for c, tire in enumerate(tires):
        _lib.fb_study_report_wheel_window(rep, c, window)
        found["wheel_windows"][tire] = (window[0], window[1])
    found["tire_models"] = {}
    for c in range(len(tires)):
        model = _lib.fb_scenario_corner_tire(s, c).decode()
        found["tire_models"][model] = found["tire_models"].get(model, 0) + 1
    cmp = _lib.fb_study_report_cmp(rep, 0)  # FB_STUDY_CMP_SYSTEM2
    if cmp:
        found["comparison"] = {
            name: OutputComparison(*(getattr(cmp[k], n) for n, _ in _OutputCmp._fields_))
            for k, name in enumerate(outputs)}
        d = _lib.fb_study_report_differences(rep, 0)
        found["differences"] = Differences(
            output(d.largest), d.nvarying, d.nnotable,
            [n for k, n in enumerate(outputs) if _lib.fb_study_report_notable(rep, 0, k)])
    found["largest_rms_change"] = output(_lib.fb_study_report_largest_rms_change(rep))
    torsion = _lib.fb_study_report_torsion_output(rep)
    found["torsion"] = output(torsion)
    factor = ctypes.c_double()
    grows = output(_lib.fb_study_report_largest_growth(rep, ctypes.byref(factor)))
    found["largest_growth"] = (grows, factor.value) if grows else None
    for i, name in enumerate(names):
        run = _lib.fb_study_report_run(rep, i)
        if found["torsion"]:
            found["torsion_max_abs"][name] = _lib.fb_study_run_max_abs(run, torsion)
        most, least = ctypes.c_size_t(), ctypes.c_size_t()
        _lib.fb_study_report_contact_extremes(rep, run, ctypes.byref(most), ctypes.byref(least))
        found["contact_extremes"][name] = (tires[most.value], tires[least.value])
    return found


def _summarised_run(s, v, reporter, window, basis_error):
    """v run (a vehicle of scenario s) and summarised over window, with its
    reduced basis's error estimate when basis_error: (result, summary,
    basis error or None)."""
    res, summary, err = ctypes.c_void_p(), ctypes.c_void_p(), _Err()
    _check(_lib.fb_vehicle_run(v, None, reporter.run_fn, None, ctypes.byref(res), None,
                               ctypes.byref(err)), err)
    run = [(res, summary, None)]
    try:
        _check(_lib.fb_run_summary_new(s, res, window, ctypes.byref(summary), ctypes.byref(err)),
               err)
        if basis_error and _lib.fb_vehicle_basis_reduced(v):
            est = (ctypes.c_double * max(1, _lib.fb_scenario_noutputs(s)))()
            _check(_lib.fb_vehicle_basis_error(v, res, window, reporter.run_fn, None, est,
                                               ctypes.byref(err)), err)
            run[0] = (res, summary, est)
        return run[0]
    except BaseException:
        _free_runs(run)
        raise


def _study_run(sys_id, handle):
    res, summary, est = handle
    return _StudyRun(sys_id, res.value, summary.value,
                     ctypes.cast(est, _PDOUBLE) if est is not None else None)


def _converged_findings(s, rep, fine, density):
    """Study's members of the converged run fine (or None) at density."""
    if not fine:
        return {"converged": None, "converged_density": None, "comparison_converged": None,
                "differences_converged": None, "mesh_crossings": 0, "mesh_diff": None}
    outputs = [_lib.fb_scenario_output_name(s, k).decode()
               for k in range(_lib.fb_scenario_noutputs(s))]
    cmp = _lib.fb_study_report_cmp(rep, 1)  # FB_STUDY_CMP_CONVERGED
    d = _lib.fb_study_report_differences(rep, 1)
    return {
        "converged": RunSummary(s, "flexible", fine[0], fine[1], fine[2]),
        "converged_density": density,
        "comparison_converged": {
            name: OutputComparison(*(getattr(cmp[k], n) for n, _ in _OutputCmp._fields_))
            for k, name in enumerate(outputs)},
        "differences_converged": Differences(
            outputs[d.largest] if d.largest < len(outputs) else None, d.nvarying, d.nnotable,
            [n for k, n in enumerate(outputs) if _lib.fb_study_report_notable(rep, 1, k)]),
        "mesh_crossings": _lib.fb_study_report_mesh_crossings(rep),
        "mesh_diff": {n: _lib.fb_study_report_mesh_diff(rep, k) for k, n in enumerate(outputs)}}


def _free_runs(handles):
    """Frees the runs [(result, summary)] of a study."""
    for res, summary, _ in handles:
        _lib.fb_run_summary_free(ctypes.byref(summary))
        _lib.fb_result_free(ctypes.byref(res))


def _stats(s):
    return OutputStats(s.static, s.peak, s.peak_time, s.min, s.min_time, s.rms)


Eigenvalues = collections.namedtuple("Eigenvalues", "values nstates zero_tol t")
Eigenvalues.__doc__ = """The eigenvalues of a graph's state equations linearised at its
initial state at time t (s), as flexbond eig lists them: values (complex,
1/s; by |imaginary part|, then real part, a pair's positive member first),
the diagram's nstates, and zero_tol (n eps ||A||_F): the nstates -
len(values) eigenvalues within it of 0 are round-off, left out."""

_VEHICLE_MEMORY_LIMIT = 4 << 30  # FB_VEHICLE_MEMORY_LIMIT, bytes


def _eigenvalues(graph, t, x0, what, on_error):
    """The Eigenvalues of graph (no probes: they do not change the state
    equations) at time t and state x0 (NULL: the graph's initial state);
    on_error(err) locates an error of the graph before it is raised."""
    bd, e, err = ctypes.c_void_p(), ctypes.POINTER(_BdEigen)(), _Err()
    try:
        if _lib.fb_bd_build(graph, None, 0, ctypes.byref(bd), ctypes.byref(err)) != 0:
            on_error(err)
            raise Error(err)
        _check(_lib.fb_bd_eigen_new(bd, t, x0, _VEHICLE_MEMORY_LIMIT, what.encode(),
                                    ctypes.byref(e), ctypes.byref(err)), err)
        n = e.contents.n if e else 0
        values = numpy.array([complex(e.contents.re[i], e.contents.im[i]) for i in range(n)])
        return Eigenvalues(values, _lib.fb_bd_nstates(bd) if bd else 0,
                           e.contents.zero_tol if e else 0.0, t)
    finally:
        _lib.fb_bd_eigen_free(ctypes.byref(e))
        _lib.fb_bd_free(ctypes.byref(bd))


MassProps = collections.namedtuple("MassProps", "mass cg inertia")
MassProps.__doc__ = """A hull's mass (kg), centre of mass (x, y, z; m, in the scenario
file's frame) and inertia tensor about it (3 x 3 numpy array, kg m^2)."""

SectionTotals = collections.namedtuple("SectionTotals", "nelements area mass")
SectionTotals.__doc__ = """The elements of one plate section: how many, their area (m^2) and
their mass (kg)."""

HullMesh = collections.namedtuple("HullMesh", "nodes tri3 quad4 sections structure as_built")
HullMesh.__doc__ = """System 2's hull mesh (Scenario.hull_mesh), as flexbond mesh prints it:
its node and element counts (S3 triangles, S4 quadrilaterals), sections
{element set: SectionTotals} when the plates differ ("hull.material" for
the elements of none; empty when they are all one), the structure's
MassProps and the hull's as built with its declared masses (None without
any)."""


def _mass_props(h, with_masses, origin):
    p, err = _HullMassProps(), _Err()
    _check(_lib.fb_fe_hull_mass_props(h, with_masses, ctypes.byref(p), ctypes.byref(err)), err)
    return MassProps(p.mass, tuple(o + x for o, x in zip(origin, p.cg)),
                     numpy.array(p.inertia).reshape(3, 3))


def _frame_offset(s):
    """Where the library's frame inside (the hull structure's centre of
    mass) lies in the scenario file's (fb_scenario_frame_offset)."""
    o = (ctypes.c_double * 3)()
    _lib.fb_scenario_frame_offset(s, ctypes.byref(o))
    return tuple(o)


def _hull_mesh(h, origin):
    """The HullMesh of the realised finite-element hull h, its positions
    moved by origin (the file's frame: _frame_offset)."""
    mesh = _lib.fb_fe_hull_mesh(h)
    sections = {}
    nsections = _lib.fb_mesh_nsections(mesh)
    for sec in range(-1, nsections) if nsections else ():
        totals = _lib.fb_fe_hull_section_totals(h, sec)
        if totals.nelements:
            name = ("hull.material" if sec < 0
                    else _lib.fb_mesh_section_elset(mesh, sec).decode(errors="replace"))
            sections[name] = SectionTotals(totals.nelements, totals.area, totals.mass)
    as_built = _mass_props(h, 1, origin) if _lib.fb_fe_hull_npoint_masses(h) else None
    return HullMesh(_lib.fb_mesh_nnodes(mesh), _lib.fb_mesh_count(mesh, 3),
                    _lib.fb_mesh_count(mesh, 4), sections, _mass_props(h, 0, origin), as_built)


HullStressPeaks = collections.namedtuple(
    "HullStressPeaks",
    "element_id section centroid von_mises time surface range range_surface nsamples t_from")
HullStressPeaks.__doc__ = """System 2's hull stresses over a run (Scenario.hull_stress_peaks), as
flexbond run's stress_peaks.csv holds them, one entry per element in the
mesh's order (numpy arrays): element_id, section (its element set's name,
"" for none), centroid (n x 3, m, the file's frame), von_mises (the peak,
the larger surface's, Pa), time (s), surface ("top" or "bottom"), range
(the largest range of a plane's normal stress, Pa) and range_surface;
nsamples, the samples taken from t_from (s) on (docs/stresses.md)."""


def _stress_peaks(s, mesh, p, t_from):
    """The HullStressPeaks of the library's peaks p over mesh."""
    n = p.nelements
    origin = _frame_offset(s)
    ids = numpy.empty(n, dtype=numpy.int64)
    centroid = numpy.empty((n, 3))
    section = []
    c = (ctypes.c_double * 3)()
    for e in range(n):
        ids[e] = _lib.fb_mesh_element_id(mesh, e)
        _lib.fb_mesh_element_centroid(mesh, e, c)
        centroid[e] = [c[k] + origin[k] for k in range(3)]
        sec = _lib.fb_mesh_element_section(mesh, e)
        section.append(_lib.fb_mesh_section_elset(mesh, sec).decode(errors="replace")
                       if sec >= 0 else "")
    surfaces = numpy.array(["top", "bottom"])
    return HullStressPeaks(ids, numpy.array(section, dtype=object), centroid,
                           numpy.ctypeslib.as_array(p.von_mises, (n,)).copy(),
                           numpy.ctypeslib.as_array(p.time, (n,)).copy(),
                           surfaces[numpy.ctypeslib.as_array(p.surface, (n,))],
                           numpy.ctypeslib.as_array(p.range, (n,)).copy(),
                           surfaces[numpy.ctypeslib.as_array(p.range_surface, (n,))],
                           p.nsamples, t_from)


HullModes = collections.namedtuple("HullModes", "hull_freq_hz nrigid vehicle nfree")
HullModes.__doc__ = """System 2's structural modes (Scenario.hull_modes): the free-free
hull's frequencies (Hz, the nrigid rigid-body ones first) and the undamped
vehicle's [(freq_hz, description)], nfree zero-frequency modes left out."""


Differences = collections.namedtuple("Differences", "largest nvarying nnotable notable")
Differences.__doc__ = """Of a comparison's outputs (flexbond/study.h): the name of the one
with the largest relative difference (None when no output varies in the
first system), how many vary there, how many of those differ by more than
NOTABLE_DIFF of the first system's range, and their names."""

NOTABLE_DIFF = 0.05    # FB_STUDY_NOTABLE_DIFF: a notable difference, of the range
NOTABLE_CHANGE = 0.05  # FB_STUDY_NOTABLE_CHANGE: a notable peak or r.m.s. change


class Study:
    """Systems of one scenario run and compared, as flexbond run does, with
    the findings its report.md states, all from the library's report data
    (fb_study_report):

    runs {system: RunSummary}; comparison {output: OutputComparison} of the
    second against the first with two systems (System 2 against System 1
    for the default ("rigid", "flexible")), else None; window, the response
    window (s); wheel_windows {tire: (entry, exit)}, when each wheel meets
    the road's feature and leaves it (s); tire_models {model: number of
    tires}; differences, a Differences with two systems, else None;
    largest_rms_change, the output whose r.m.s. changes the most (None
    without a comparison); torsion, the torsion angle's output (None when
    none) and torsion_max_abs {system: its largest |value| over the run};
    largest_growth (output, peak / static) of the first system, the output
    that grows the most relative to its static value (None when none); and
    contact_extremes {system: (tire, tire)}, the tire whose peak reaction is
    the largest multiple of its static one and the one with the smallest
    reaction over the window; mesh_error, the estimated band (low, high) by
    which a generated hull's first elastic free-free frequencies lie above
    their converged values, as fractions (None for a deck or without a
    finite-element hull)."""

    def __init__(self, runs, comparison, **findings):
        self.runs = runs
        self.comparison = comparison
        self.__dict__.update(findings)

Mode = collections.namedtuple("Mode", "eigenvalue freq_hz damping_ratio description")
Mode.__doc__ = """A mode: eigenvalue (complex, 1/s), freq_hz (|lambda| / 2 pi, or
Im(lambda) / 2 pi undamped), damping_ratio (-Re / |lambda|) and a description
from its largest kinetic-energy share ("hull bounce (62%)")."""


class Sweep:
    """A parameter study's cases (Scenario.sweep), with the numbers flexbond
    sweep writes in sweep.csv: keys (the swept keys, as given), metrics (the
    metric columns in sweep.csv's order: each output's peak, min and rms,
    min_tire_force, contact_loss_intervals, the ride metrics, solver_steps),
    units {metric: unit} ("-" for a count or a ratio), and cases: a dict per
    case in grid order (the first key varying slowest) of each key's value
    (its text, as the scenario reads it), each metric (a float, NaN where
    sweep.csv's cell is empty: a failed case, a metric the run does not
    define) and "error" (None, or the case's message). sweep[name] is a
    column over the cases (a numpy array for a metric); failed lists the
    failed cases' indices."""

    def __init__(self, system, keys, metrics, units, cases):
        self.system, self.keys, self.metrics, self.units = system, keys, metrics, units
        self.cases = cases
        self.failed = [i for i, c in enumerate(cases) if c["error"] is not None]

    @property
    def columns(self):
        """sweep.csv's columns: the keys, the metrics and "error"."""
        return self.keys + self.metrics + ["error"]

    def __len__(self):
        return len(self.cases)

    def __getitem__(self, name):
        if name not in self.columns:
            raise KeyError("flexbond: no column %r (the columns: %s)" %
                           (name, ", ".join(self.columns)))
        column = [c[name] for c in self.cases]
        return numpy.array(column, dtype=float) if name in self.units else column

    def __repr__(self):
        return "Sweep(%s, %d cases over %s, %d failed)" % (
            self.system, len(self.cases), ", ".join(self.keys), len(self.failed))


def _sweep_stage(sw, keys, i):
    """A finished case's progress line, as flexbond sweep says it."""
    c = _SweepCase()
    _lib.fb_study_sweep_case_get(sw, i, ctypes.byref(c))
    label = ", ".join("%s=%s" % (k, _lib.fb_study_sweep_case_value(sw, i, j).decode())
                      for j, k in enumerate(keys))
    what = "ok" if c.status == 0 else "failed: %s" % (
        c.error.decode(errors="replace") if c.error else "out of memory")
    return "case %d/%d (%s): %s" % (i + 1, _lib.fb_study_sweep_ncases(sw), label, what)


def _sweep(sw, keys, system):
    """The Sweep of a run fb_study_sweep."""
    names, units = [], {}
    buf = ctypes.create_string_buffer(512)
    nmetrics = _lib.fb_study_sweep_nmetrics(sw)
    for m in range(nmetrics):
        _lib.fb_study_sweep_metric_name(sw, m, buf, len(buf))
        names.append(buf.value.decode())
        units[names[-1]] = _lib.fb_study_sweep_metric_unit(sw, m).decode()
    cases = []
    for i in range(_lib.fb_study_sweep_ncases(sw)):
        c = _SweepCase()
        _lib.fb_study_sweep_case_get(sw, i, ctypes.byref(c))
        case = {k: _lib.fb_study_sweep_case_value(sw, i, j).decode() for j, k in enumerate(keys)}
        case.update((n, c.metric[m]) for m, n in enumerate(names))
        case["error"] = None if c.status == 0 else (
            c.error.decode(errors="replace") if c.error else "out of memory")
        cases.append(case)
    return Sweep(system, keys, names, units, cases)


class Modes(list):
    """The modes, oscillatory first by frequency; nstatic counts the zero
    eigenvalues of a statically indeterminate support, left out."""

    def __init__(self, modes, nstatic):
        super().__init__(modes)
        self.nstatic = nstatic


class FreqResponse:
    """H[k, o, t]: the complex amplitude of output names[o] per metre of road
    height on track t (0 left, 1 right) at freq_hz[k], the wheels seeing the
    profile delayed by their distance behind the first. units[o] is the
    output's unit; H's is units[o] per metre. magnitude and phase_deg are
    |H| and its phase in degrees, (-180, 180], as flexbond freq writes them;
    peaks {name: (|H|, freq_hz, track)} each output's largest |H| and where,
    as it prints them. Power outputs, products of two signals, have no
    frequency response and are left out (skipped)."""

    def __init__(self, system, freq_hz, names, units, H, skipped, linearised, peaks):
        self.system = system
        self.freq_hz = freq_hz
        self.names = names
        self.units = units
        self.H = H
        self.skipped = skipped
        self.linearised = linearised
        self.peaks = peaks
        self.tracks = TRACKS

    @property
    def magnitude(self):
        return numpy.abs(self.H)

    @property
    def phase_deg(self):
        return numpy.degrees(numpy.angle(self.H))

    def __getitem__(self, name):
        try:
            return self.H[:, self.names.index(name), :]
        except ValueError:
            raise KeyError("flexbond: no frequency response of %r; there are %s"
                           % (name, ", ".join(self.names))) from None

    def __repr__(self):
        return "<flexbond.FreqResponse %s: %d outputs at %d frequencies>" % (
            self.system, len(self.names), len(self.freq_hz))


PsdRoad = collections.namedtuple("PsdRoad", "road_class gd0 band speed tracks")
PsdRoad.__doc__ = """The ISO 8608 road of a RidePSD: its class ("A" .. "H"), gd0 (m^3,
the displacement PSD at 0.1 cycles/m), band (n_min, n_max) in cycles/m, speed
(m/s) and tracks ("independent" or "identical")."""


class RidePSD:
    """The ride from a road spectrum (Scenario.ride_psd), as flexbond freq
    computes it on an ISO 8608 road without a time run: road (a PsdRoad),
    freq_hz (the band's frequencies, Hz), road_psd (the road's temporal PSD
    per track, m^2/Hz), psd {name: each output's PSD, unit^2/Hz}, rms {name:
    its r.m.s. over the band}, a_w (m/s^2, the ISO 2631-1 weighted r.m.s. of
    a_w_output, the first mounted body's acceleration; None without one)
    and weighted (that output's Wk-weighted PSD, or None): ride_psd.json's
    and psd_systemN.csv's numbers. Power outputs have none (skipped)."""

    def __init__(self, system, road, linearised, freq_hz, road_psd, psd, rms, a_w_output,
                 weighted, a_w, skipped):
        self.system, self.road, self.linearised = system, road, linearised
        self.freq_hz, self.road_psd, self.psd, self.rms = freq_hz, road_psd, psd, rms
        self.a_w_output, self.weighted, self.a_w = a_w_output, weighted, a_w
        self.skipped = skipped

    def __repr__(self):
        return "<flexbond.RidePSD %s: ISO 8608 class %s, a_w %s>" % (
            self.system, self.road.road_class, "none" if self.a_w is None else
            "%.4g m/s^2" % self.a_w)


def _array(ptr, n):
    """A copy of n doubles the library owns."""
    return numpy.ctypeslib.as_array(ptr, shape=(n,)).copy()


def _freq_response(name, outs, f):
    """The FreqResponse of study f (fb_study_freq), copied out of it."""
    n = _lib.fb_study_freq_nfreq(f)
    freq_hz = _array(_lib.fb_study_freq_hz(f), n) if n else numpy.empty(0)
    keep = [o for o in range(len(outs)) if _lib.fb_study_freq_has_output(f, o)]
    H = numpy.empty((n, len(keep), _NTRACKS), dtype=complex)
    peaks = {}
    for i, o in enumerate(keep):
        for t in range(_NTRACKS):
            for k in range(n):
                z = _lib.fb_study_freq_at(f, o, t, k)
                H[k, i, t] = complex(z[0], z[1])
        k, track = ctypes.c_size_t(), ctypes.c_int()
        big = _lib.fb_study_freq_peak(f, o, ctypes.byref(k), ctypes.byref(track))
        if n:
            peaks[outs[o][0]] = (big, freq_hz[k.value], TRACKS[track.value])
    skipped = [outs[o][0] for o in range(len(outs)) if o not in keep]
    return FreqResponse(name, freq_hz, [outs[o][0] for o in keep], [outs[o][1] for o in keep],
                        H, skipped, bool(_lib.fb_study_freq_linearised(f)), peaks)


def _ride_psd(name, outs, r):
    """The RidePSD of ride r (fb_study_ride_psd), copied out of it."""
    road = _lib.fb_study_ride_psd_road(r).contents
    n = _lib.fb_study_ride_psd_nfreq(r)
    psd, rms, skipped = {}, {}, []
    for o, (oname, _unit) in enumerate(outs):
        p = _lib.fb_study_ride_psd_output(r, o)
        if not p:
            skipped.append(oname)
            continue
        psd[oname] = _array(p, n)
        rms[oname] = _lib.fb_study_ride_psd_rms(r, o)
    acc = _lib.fb_study_ride_psd_a_w_output(r)
    weighted = _lib.fb_study_ride_psd_weighted(r)
    return RidePSD(name,
                   PsdRoad(road.road_class.decode(), road.gd0, (road.n_min, road.n_max),
                           road.speed, "identical" if road.identical else "independent"),
                   bool(_lib.fb_study_ride_psd_linearised(r)),
                   _array(_lib.fb_study_ride_psd_hz(r), n),
                   _array(_lib.fb_study_ride_psd_road_psd(r), n), psd, rms,
                   outs[acc][0] if acc < len(outs) else None,
                   _array(weighted, n) if weighted else None,
                   _lib.fb_study_ride_psd_a_w(r) if weighted else None, skipped)


class Model:
    """The vehicle's linear descriptor model E x' = A x + B u + f,
    y = C x + D u (docs/export.md), tires held in contact; with linearised,
    at the static equilibrium (x, u and y deviations, f zero). E, A, B, f, C
    and D are scipy.sparse CSC matrices. var_names has n names, the first
    nstates differential; input_names names B's columns (each wheel's road
    rate); output_rows[o] lists the rows of C making output output_names[o]
    (two for a power output, their product)."""

    def __init__(self, system, **fields):
        self.system = system
        self.__dict__.update(fields)

    def __repr__(self):
        return "<flexbond.Model %s: %d variables (%d differential), %d inputs, %d outputs>" % (
            self.system, len(self.var_names), self.nstates, len(self.input_names),
            len(self.output_names))


def _sparse(mat):
    import scipy.sparse  # only the exported model needs scipy (python3-scipy)
    nnz = _lib.fb_mat_nnz(mat)
    rows = numpy.empty(nnz, dtype=numpy.uintp)
    cols = numpy.empty(nnz, dtype=numpy.uintp)
    vals = numpy.empty(nnz)
    got = _lib.fb_mat_triplets(mat, rows.ctypes.data_as(_PSIZE), cols.ctypes.data_as(_PSIZE),
                               vals.ctypes.data_as(_PDOUBLE))
    shape = (_lib.fb_mat_nrows(mat), _lib.fb_mat_ncols(mat))
    return scipy.sparse.csc_matrix((vals[:got], (rows[:got], cols[:got])), shape=shape)


def _strings(array, n):
    return [array[i].decode() for i in range(n)]


class _Reporter:
    """The progress of one call: progress(stage, fraction), the caller's
    function (None: none), hears each stage of the set-up (System 2's
    assembly, factorisation, eigen-solve and basis, with the library's own
    words) and every solver step ("simulating System 1 (rigid hull), t =
    0..15 s", t / t_end). An exception it raises stops the library at its
    next report and reaches the caller; so does a Ctrl-C (stop, the list
    _until_done appends to)."""

    def __init__(self, progress, stop, label):
        self.progress, self.stop, self.label, self.error = progress, stop, label, None
        # The ctypes callbacks, kept alive while the library may call them.
        self.stage_fn = _STAGE_PROGRESS(self._stage)
        self.run_fn = _PROGRESS(self._run)

    def _report(self, stage, fraction):
        if self.progress is not None and self.error is None:
            try:
                self.progress(stage, fraction)
            except BaseException as e:  # raised to the caller when the library stops
                self.error = e
        return 1 if self.stop or self.error is not None else 0

    def _stage(self, _ctx, stage, fraction):
        return self._report(stage.decode(errors="replace"), fraction)

    def _run(self, _ctx, t, t_end):
        return self._report("simulating %s, t = 0..%g s" % (self.label, t_end),
                            t / t_end if t_end > 0 else 1.0)


def _until_done(work, on_no_start=None):
    """work(stop) on a thread of its own, the caller waiting: a Ctrl-C
    (KeyboardInterrupt) or any other exception in the caller reaches it at
    once, whatever the library is doing, and asks work to stop (stop, the
    list the progress callbacks see, gets an entry). The library stops at
    its next progress report (a solver step, a stage of the hull's
    eigen-solve); what work computes after that is dropped. on_no_start()
    runs if the thread cannot start. Returns work's value or raises its
    exception."""
    stop, box = [], {}

    def run():
        try:
            box["value"] = work(stop)
        except BaseException as e:  # handed to the caller
            box["error"] = e

    thread = threading.Thread(target=run, name="flexbond", daemon=True)
    try:
        thread.start()
    except BaseException:
        if on_no_start is not None:
            on_no_start()
        raise
    try:
        while thread.is_alive():
            thread.join(0.05)
    except BaseException:
        stop.append(True)
        raise
    if "error" in box:
        raise box["error"]
    return box["value"]


# ---- Scenarios.

def _overrides(items):
    """(key, value) pairs as an fb_scenario_override array and its length.
    An error about an override names it as the caller wrote it:
    overrides['speed_kmh']=-5, not flexbond's --set."""
    keep = [(_c_text(k, "override key"), _c_text(_text(v), "override value", key=k),
             _c_text("overrides[%r]=%r" % (k, v), "override key"))
            for k, v in items]
    return (_Override * max(1, len(keep)))(*[_Override(*o) for o in keep]), len(keep)


class _Closing:
    """close() when a with block ends and when collected (not at interpreter
    exit, the library gone)."""

    def __del__(self):
        if _lib is not None:
            self.close()

    def __enter__(self):
        return self

    def __exit__(self, *exc):
        self.close()


class Scenario(_Closing):
    """A scenario file (docs/scenario-format.md), loaded and checked, with
    overrides: {key: value}, each key a key path of the file
    ("road.speed_kmh") or a key name that names one ("speed_kmh"), each value
    a number or text as the file would write it (flexbond run --set).
    Implausible values (a 20 m plate, a tire of 1 N/m) are warnings
    (PlausibilityWarning, and the list warnings); strict=True raises Error
    at the first, as flexbond's --strict."""

    def __init__(self, path, overrides=None, strict=False):
        self._begin(os.fspath(path))
        self.overrides = dict(overrides or {})
        ov, n = _overrides(self.overrides.items())
        err = _Err()
        _check(_lib.fb_scenario_load_overrides(_c_text(self.path, "path"), ov, n,
                                               ctypes.byref(self._s), ctypes.byref(err)), err)
        self._warn(strict, Error)

    @classmethod
    def from_dict(cls, description, name="description", strict=False):
        """A vehicle described by Python data rather than a file: description
        holds what a scenario file would (docs/scenario-format.md: the same
        keys, lists and values, numbers as numbers or expressions as text;
        relative file names resolve from the current directory). It is read
        and checked as a file is; an error or warning names the value by its
        path in the data, "description['road']['speed_kmh']: ...", in
        Error.path, and name is the data's name in those paths."""
        self = cls.__new__(cls)
        self._begin("<%s>" % name)
        self._data_name = name
        try:
            text = json.dumps(description, indent=1, ensure_ascii=False)
        except (TypeError, ValueError) as e:
            raise ValueError("flexbond: the description is not plain data: %s" % e) from None
        data = _c_text(text, "description")
        self._text = data  # a sweep reads it again for each case
        err = _Err()
        if _lib.fb_scenario_load_string(data, len(data), _c_text(self.path, "name"),
                                        ctypes.byref(self._s), ctypes.byref(err)) != 0:
            raise _in_data(Error(err), err, name)
        self._warn(strict, lambda e: _in_data(Error(e), e, name))
        return self

    def _begin(self, path):
        self._data_name = None
        self.overrides = None  # a file's: {key: value}, as given
        self._text = None  # a description's document (from_dict)
        self._s = ctypes.c_void_p()
        # Calls running on their threads (_with_vehicle): close() waits for them.
        self._calls = threading.Condition()
        self._ncalls = 0
        self.path = path

    def _warn(self, strict, error_of):
        """The loaded scenario's plausibility warnings (error_of makes each
        an Error): warned, or with strict the first raised."""
        # Copied out of the scenario, which close() frees.
        found = [error_of(_lib.fb_scenario_warning(self._s, i).contents)
                 for i in range(_lib.fb_scenario_nwarnings(self._s))]
        if strict and found:
            self.close()
            first = found[0]
            first.message += (" (strict=True refuses implausible values: %d in this "
                              "scenario)" % len(found))
            first.args = (first.message,)
            raise first
        self.warnings = [w.message for w in found]
        for message in self.warnings:
            warnings.warn(message, PlausibilityWarning, stacklevel=2)

    def close(self):
        """Frees the scenario (also done when it is garbage-collected), once
        the calls a Ctrl-C left running on their threads have stopped. Under
        the calls' lock: a call starting meanwhile finds it closed."""
        calls = getattr(self, "_calls", None)
        if calls is None:
            return
        with calls:
            calls.wait_for(lambda: self._ncalls == 0)
            if self._s:
                _lib.fb_scenario_free(ctypes.byref(self._s))

    def _handle(self):
        if not self._s:
            raise ValueError("flexbond: the scenario is closed")
        return self._s

    @property
    def outputs(self):
        """The scenario's outputs: [(name, unit), ...], in order."""
        s = self._handle()
        return [(_lib.fb_scenario_output_name(s, o).decode(),
                 _lib.fb_scenario_output_unit(s, o).decode())
                for o in range(_lib.fb_scenario_noutputs(s))]

    @property
    def corners(self):
        """The corners: [Corner(name, x, y), ...] (attachment points, m, in
        the file's frame: as the file wrote them), in the scenario's order."""
        s = self._handle()
        out = []
        for c in range(_lib.fb_scenario_ncorners(s)):
            x, y = ctypes.c_double(), ctypes.c_double()
            _lib.fb_scenario_corner_position(s, c, ctypes.byref(x), ctypes.byref(y))
            out.append(Corner(_lib.fb_scenario_corner_name(s, c).decode(), x.value, y.value))
        return out

    @property
    def speed(self):
        """The road speed, m/s."""
        return _lib.fb_scenario_speed(self._handle())

    def run(self, system, progress=None):
        """Simulates one system ("rigid" or "flexible") as flexbond run does:
        a Result with t, the scenario's outputs and each tire's
        contact_force_<CORNER>. Ctrl-C raises KeyboardInterrupt at once,
        in the set-up (System 2's hull eigen-solve) or between solver steps,
        and stops the library at its next report. progress(stage, fraction),
        when given, hears each stage and step; an exception it raises stops
        the run and reaches the caller."""
        name = _SYSTEM_NAMES[_system(system)]

        def use(v, reporter):
            res = ctypes.c_void_p()
            err = _Err()
            _check(_lib.fb_vehicle_run(v, None, reporter.run_fn, None, ctypes.byref(res), None,
                                       ctypes.byref(err)), err)
            try:
                return _result(res, name)
            finally:
                _lib.fb_result_free(ctypes.byref(res))

        return self._with_vehicle(system, use, progress=progress)

    def study(self, systems=("rigid", "flexible"), progress=None, basis_error=False,
              converged=False):
        """Runs each of systems (one or two) and summarises it with the
        library's study layer, and compares two (flexbond/study.h): a Study,
        the numbers flexbond run writes in summary.json. progress as run's.
        basis_error: also estimate the error of System 2's reduced modal
        basis, as flexbond run does (a second run with the basis's next
        block of Ritz vectors, fb_vehicle_basis_error). converged: with both
        systems, also run System 2 again on the hull refined to the
        scenario's hull.mesh.converged_density, as flexbond run does when it
        is above hull.mesh.density (a scenario loaded from a file)."""
        names = [_SYSTEM_NAMES[_system(s)] for s in systems]
        if not 1 <= len(names) <= 2:
            raise ValueError("flexbond: study takes one or two systems, got %d" % len(names))

        window = (ctypes.c_double * 2)()
        handles, fine = [], []
        # The scenario stays open until the summaries are read.
        with self._held(), contextlib.ExitStack() as cleanup:
            cleanup.callback(_free_runs, handles)
            cleanup.callback(_free_runs, fine)
            _lib.fb_study_response_window(self._s, window)
            for system in systems:
                handles.append(self._with_vehicle(
                    system, lambda v, r: _summarised_run(self._s, v, r, window, basis_error),
                    progress=progress))
            density = _lib.fb_scenario_converged_density(self._s)
            if converged and len(handles) == 2 and density and self._data_name is None:
                fine.append(self._converged_run(density, window, basis_error, progress))
            runs = {n: RunSummary(self._s, n, res, summary, est)
                    for n, (res, summary, est) in zip(names, handles)}
            return self._report(names, handles, runs, fine[0] if fine else None, density)

    def _converged_run(self, density, window, basis_error, progress):
        """System 2 of the file loaded again with hull.mesh.density at
        density, in the automatic modal basis (fb_scenario_use_auto_basis),
        summarised over this scenario's window: (result, summary, basis
        error or None), as flexbond run's rerun."""
        overrides = dict(self.overrides)
        overrides["hull.mesh.density"] = density
        with warnings.catch_warnings():  # this scenario's warnings, said once
            warnings.simplefilter("ignore", PlausibilityWarning)
            refined = Scenario(self.path, overrides)
        with refined:
            _lib.fb_scenario_use_auto_basis(refined._s)
            return refined._with_vehicle(
                "flexible", lambda v, r: _summarised_run(refined._s, v, r, window, basis_error),
                progress=progress)


    @contextlib.contextmanager
    def _held(self):
        """The scenario's handle, counted as a call from here to the block's
        end, so that close() waits for it."""
        with self._calls:
            s = self._handle()
            self._ncalls += 1
        try:
            yield s
        finally:
            with self._calls:
                self._ncalls -= 1
                self._calls.notify_all()

    @contextlib.contextmanager
    def _fe_hull(self):
        """System 2's finite-element hull of the scenario (fb_vehicle_fe_hull),
        freed at the block's end."""
        with self._held() as s:
            h, err = ctypes.c_void_p(), _Err()
            _check_about(s, _lib.fb_vehicle_fe_hull(s, ctypes.byref(h), ctypes.byref(err)), err,
                         self._data_name)
            try:
                yield h
            finally:
                _lib.fb_fe_hull_free(ctypes.byref(h))

    def _report(self, names, handles, runs, fine, density):
        """The Study of the runs handles [(result, summary, basis error)] of
        systems names and of System 2 on the converged mesh (fine, or None),
        from the library's report data (fb_study_report)."""
        study_runs = (_StudyRun * len(handles))(
            *(_study_run(_SYSTEMS[n], h) for n, h in zip(names, handles)))
        conv = _study_run(FLEXIBLE, fine) if fine else None
        rep, err = ctypes.c_void_p(), _Err()
        _check(_lib.fb_study_report_new(self._s, study_runs, len(handles),
                                        ctypes.byref(conv) if conv else None,
                                        ctypes.byref(rep), ctypes.byref(err)), err)
        try:
            found = _findings(self._s, rep, names)
            found.update(_converged_findings(self._s, rep, fine, density))
            return Study(runs, **found)
        finally:
            _lib.fb_study_report_free(ctypes.byref(rep))

    def eigenvalues(self, system="rigid"):
        """The eigenvalues of system's graph linearised at its initial state
        (every state 0) and start time, as flexbond eig lists them
        (fb_bd_eigen_new): Eigenvalues. modes() linearises at the static
        equilibrium instead."""
        sys_id = _system(system)
        graph, probes, nprobes, err = ctypes.c_void_p(), ctypes.c_void_p(), ctypes.c_size_t(), \
            _Err()
        with self._held() as s:  # open until the graph is made
            try:
                _check_about(s, _lib.fb_vehicle_graph(s, sys_id, ctypes.byref(graph),
                                                      ctypes.byref(probes), ctypes.byref(nprobes),
                                                      ctypes.byref(err)), err, self._data_name)
                opts = _SimOpts()
                _lib.fb_vehicle_sim_opts(s, ctypes.byref(opts))
                return _eigenvalues(graph, opts.t_start, opts.x0,
                                    "eigenvalues of " + _SYSTEM_NAMES[sys_id], lambda err: None)
            finally:
                _lib.fb_vehicle_probes_free(ctypes.byref(probes), nprobes.value)
                _lib.fb_bg_free(ctypes.byref(graph))

    def hull_mesh(self):
        """System 2's finite-element hull as flexbond mesh builds and
        describes it (its source's: the generator, a deck or a reduced
        structure's superelement, checked): a HullMesh, from
        the same library calls (fb_fe_hull_mass_props,
        fb_fe_hull_section_totals). Error when the scenario has no
        finite-element hull."""
        with self._fe_hull() as h:
            return _hull_mesh(h, _frame_offset(self._handle()))

    def hull_stress_peaks(self, t_from=None, progress=None):
        """System 2 run as Scenario.run("flexible") does, and its hull's
        stresses over the run's output samples from t_from (s; None: the
        road window's start, as flexbond run takes): a HullStressPeaks,
        flexbond run's stress_peaks.csv from the same library calls
        (fb_hull_stress_peaks_of). progress as for run. Error when the
        scenario has no finite-element hull."""
        if t_from is None:
            window = (ctypes.c_double * 2)()
            with self._held():
                _lib.fb_study_response_window(self._s, window)
            t_from = window[0]

        def body(s, sys_id, opts, reporter):
            opts.motion = 2  # FB_VEHICLE_MOTION_HULL: the results are run()'s
            v, res, motion, hs = ctypes.c_void_p(), ctypes.c_void_p(), ctypes.c_void_p(), \
                ctypes.c_void_p()
            peaks = ctypes.POINTER(_HullStressPeaks)()
            err = _Err()
            try:
                _check_about(s, _lib.fb_vehicle_new(s, sys_id, ctypes.byref(opts),
                                                    ctypes.byref(v), ctypes.byref(err)),
                             err, self._data_name)
                _check(_lib.fb_vehicle_run(v, None, reporter.run_fn, None, ctypes.byref(res),
                                           ctypes.byref(motion), ctypes.byref(err)), err)
                _check(_lib.fb_hull_stress_new(v, ctypes.byref(hs), ctypes.byref(err)), err)
                _check(_lib.fb_hull_stress_peaks_of(hs, motion, ctypes.c_double(t_from),
                                                    ctypes.byref(peaks), ctypes.byref(err)),
                       err)
                return _stress_peaks(s, _lib.fb_hull_stress_mesh(hs), peaks.contents, t_from)
            finally:
                _lib.fb_hull_stress_peaks_free(ctypes.byref(peaks))
                _lib.fb_hull_stress_free(ctypes.byref(hs))
                _lib.fb_vehicle_motion_free(ctypes.byref(motion))
                _lib.fb_result_free(ctypes.byref(res))
                _lib.fb_vehicle_free(ctypes.byref(v))

        return self._in_call("flexible", body, 0, progress)

    def hull_matrices(self):
        """The hull structure's own stiffness and mass matrices (K, M; N/m
        and kg, six DOFs per node in node order, the hull.masses left out)
        as scipy.sparse matrices: flexbond mesh --export-matrices's K.mtx
        and M.mtx, from the same library call (fb_fe_hull_matrices)."""
        with self._fe_hull() as h:
            K, M, err = ctypes.c_void_p(), ctypes.c_void_p(), _Err()
            try:
                _check(_lib.fb_fe_hull_matrices(h, ctypes.byref(K), ctypes.byref(M),
                                                ctypes.byref(err)), err)
                return _sparse(K), _sparse(M)
            finally:
                _lib.fb_mat_free(ctypes.byref(K))
                _lib.fb_mat_free(ctypes.byref(M))

    def hull_modes(self, nhull=30, nvehicle=20, progress=None):
        """System 2's structural modes, as flexbond modes --system flexible
        lists them: a HullModes with the free-free hull's lowest nhull
        frequencies (hull_freq_hz, Hz; its nrigid rigid-body ones first) and
        the undamped vehicle's lowest nvehicle modes from its sparse nodal
        model (vehicle: [(freq_hz, description)], the nfree horizontal
        rigid-body modes of zero frequency left out). progress as run's."""
        def use(v, _stop):
            freq = _PDOUBLE()
            nrigid = ctypes.c_size_t()
            n = _lib.fb_vehicle_hull_free_modes(v, ctypes.byref(freq), ctypes.byref(nrigid))
            hull = [freq[k] for k in range(min(n, int(nhull)))]
            ms = ctypes.POINTER(_ModeSet)()
            err = _Err()
            _check(_lib.fb_vehicle_structural_modes(v, int(nvehicle), 1, ctypes.byref(ms),
                                                    ctypes.byref(err)), err)
            try:
                m = ms.contents
                vehicle = [(m.freq_hz[k], m.description[k].value.decode(errors="replace"))
                           for k in range(m.nmodes)]
                return HullModes(hull, nrigid.value, vehicle, m.nfree)
            finally:
                _lib.fb_mode_set_free(ctypes.byref(ms))

        return self._with_vehicle("flexible", use, hull_modes=int(nhull), progress=progress)

    def sweep(self, axes, system="rigid", threads=None, progress=None):
        """A parameter study, as flexbond sweep runs it (docs/sweep.md): the
        scenario once per combination of axes' values ({key: [value, ...]},
        keys and values as overrides take them; the first key varies
        slowest), each case read with its values after the scenario's own
        overrides (one of a swept key is replaced), simulated with system
        and measured by the library's study layer (fb_study_sweep) on
        threads threads (default: the CPUs). A case that fails keeps its
        message and the others go on. Returns a Sweep: sweep.csv's columns.
        progress(stage, fraction), when given, hears each finished case
        ("case 3/12 (speed_kmh=15): ok", cases finished / cases); an
        exception it raises stops the sweep and reaches the caller, as
        Ctrl-C does."""
        sys_id = _system(system)
        axes = dict(axes)
        if isinstance(threads, bool) or (threads is not None and int(threads) < 1):
            raise ValueError("flexbond: threads must be a positive integer, got %r" % (threads,))
        nthreads = int(threads) if threads is not None else (os.cpu_count() or 1)
        keys = list(axes)
        values = []
        for k in keys:
            if isinstance(axes[k], (str, bytes)):
                raise TypeError("flexbond: sweep axis %r: a list of values, not one text" % k)
            texts = [_text(v) for v in axes[k]]
            values.append(((ctypes.c_char_p * max(1, len(texts)))(
                *[_c_text(t, "sweep value", key=k) for t in texts]), len(texts)))
        axis = (_SweepAxis * max(1, len(keys)))(
            *[_SweepAxis(_c_text(k, "sweep key"), v, n) for k, (v, n) in zip(keys, values)])
        base_ov, nbase = _overrides((k, v) for k, v in (self.overrides or {}).items()
                                    if k not in axes)
        # A case's error names its value as the caller wrote the axes:
        # axes['wheel.tire_k']=-1, not flexbond's --set.
        src = _SweepSource(None if self._text else _c_text(self.path, "path"), self._text,
                           len(self._text or b""), _c_text(self.path, "name"), base_ov, nbase,
                           b"axes")
        with self._calls:  # open, and counted, at once: close() waits for the sweep
            s = self._handle()
            self._ncalls += 1
        held = {"sw": None}  # the sweep while it runs, for a Ctrl-C to cancel
        lock = threading.Lock()
        seen = {"finished": 0, "error": None}

        def finished(_ctx, i, err):
            try:
                if progress is not None:
                    seen["finished"] += 1
                    progress(_sweep_stage(held["sw"], keys, i),
                             seen["finished"] / _lib.fb_study_sweep_ncases(held["sw"]))
                return 0
            except BaseException as e:  # raised to the caller once the sweep has stopped
                seen["error"] = e
                err.contents.code = _FB_EINTR
                err.contents.msg = b"stopped by the progress function"
                return _FB_EINTR

        finished_fn = _SWEEP_FINISHED(finished)

        def done():
            with self._calls:
                self._ncalls -= 1
                self._calls.notify_all()

        def work(_stop):
            sw, err, ops = ctypes.c_void_p(), _Err(), _SweepOps()
            try:
                _lib.fb_scenario_sweep_ops(ctypes.byref(src), ctypes.byref(ops))
                ops.finished = finished_fn
                _check(_lib.fb_study_sweep_new(s, sys_id, axis, len(keys), ctypes.byref(ops),
                                               ctypes.byref(sw), ctypes.byref(err)), err)
                with lock:
                    held["sw"] = sw
                rc = _lib.fb_study_sweep_run(sw, nthreads, ctypes.byref(err))
                if seen["error"] is not None:
                    raise seen["error"]
                _check(rc, err)
                return _sweep(sw, keys, _SYSTEM_NAMES[sys_id])
            finally:
                with lock:
                    held["sw"] = None
                _lib.fb_study_sweep_free(ctypes.byref(sw))
                done()

        try:
            return _until_done(work, on_no_start=done)
        except BaseException:
            with lock:
                if held["sw"]:
                    _lib.fb_study_sweep_cancel(held["sw"])
            raise

    def ride_limit(self, key, values, metric, limit=None, output=None, speeds_kmh=(5, 80),
                   coarse_step_kmh=5, tolerance_kmh=0.1, refine=1, course_length=200,
                   settle=2, systems=("rigid",), threads=None):
        """Ride-limiting speeds, as flexbond ride-limit finds them
        (docs/ride-limit.md): for each of values at key (overrides' texts)
        and each of systems, the highest speed within speeds_kmh below which
        metric ("a_w_rms", "abs_peak", "absorbed_power", ...; its standard
        limit unless limit is given) of output (default: the first mounted
        body's acceleration) stays under the limit, by the library's search
        (fb_study_ride_limit) on the same runs: each read from this
        scenario's file with the value, the speed and the run's end
        (fb_study_ride_limit_duration), a round's runs on threads threads
        (default: the CPUs). Returns [RideLimit, ...], ride_limit.csv's
        rows in its order: speeds in km/h (None unless found), status
        "found", "below", "above" or "failed". Ctrl-C stops it."""
        if self._text is not None:
            raise ValueError("flexbond: ride_limit reads a scenario file, not a description")
        values = [_text(v) for v in values]
        sys_ids = [_system(x) for x in systems]
        m = ctypes.c_size_t()
        if _lib.fb_study_ride_limit_metric_find(_c_text(metric, "metric"), ctypes.byref(m)):
            raise ValueError("flexbond: no ride-limit metric %r" % (metric,))
        opts = _RideLimitOpts()
        _lib.fb_study_ride_limit_opts_default(ctypes.byref(opts))
        opts.limit = (float(limit) if limit is not None
                      else _lib.fb_study_ride_limit_metric_limit(m.value))
        opts.v_lo, opts.v_hi = speeds_kmh[0] / 3.6, speeds_kmh[1] / 3.6
        opts.coarse_step, opts.tol = coarse_step_kmh / 3.6, tolerance_kmh / 3.6
        opts.refine_points = int(refine)
        names = [n for n, _ in self.outputs]
        k = names.index(output) if output is not None else \
            _lib.fb_study_ride_output(self._handle())
        if k >= len(names):
            raise ValueError("flexbond: ride_limit: no output %r" % (output,))
        nthreads = int(threads) if threads is not None else (os.cpu_count() or 1)
        path = _c_text(self.path, "path")
        base = [(k_, v) for k_, v in (self.overrides or {}).items() if k_ != key]
        errors = {}

        def one(curve, speed, stop):
            """Curve's metric at speed (m/s): NaN, its message kept, on failure."""
            if stop:
                raise KeyboardInterrupt
            ov, n = _overrides(base + [(key, values[curve % len(values)]),
                                       ("road.speed_kmh", "%.17g" % (speed * 3.6)),
                                       ("simulation.t_end", "3600")])
            sc, res, err, value = ctypes.c_void_p(), ctypes.c_void_p(), _Err(), ctypes.c_double()
            try:
                rc = _lib.fb_scenario_load_overrides(path, ov, n, ctypes.byref(sc),
                                                     ctypes.byref(err))
                if rc == 0:
                    rc = _lib.fb_study_ride_limit_duration(sc, float(course_length),
                                                           float(settle), ctypes.byref(err))
                if rc == 0:
                    rc = _lib.fb_vehicle_simulate(sc, sys_ids[curve // len(values)],
                                                  ctypes.byref(res), ctypes.byref(err))
                if rc == 0:
                    rc = _lib.fb_study_ride_limit_measure(sc, res, k, m.value,
                                                          ctypes.byref(value), ctypes.byref(err))
                if rc != 0 or math.isnan(value.value):
                    errors.setdefault(curve, "at %.4g km/h: %s" % (
                        speed * 3.6, err.msg.decode(errors="replace") if rc != 0 else
                        "the metric is not defined"))
                    return math.nan
                return value.value
            finally:
                _lib.fb_result_free(ctypes.byref(res))
                _lib.fb_scenario_free(ctypes.byref(sc))

        def work(stop):
            box = {}

            def evaluate(_ctx, pts, n, out, _err):
                try:
                    with concurrent.futures.ThreadPoolExecutor(max(1, nthreads)) as pool:
                        got = list(pool.map(lambda i: one(pts[i].curve, pts[i].speed, stop),
                                            range(n)))
                    for i, v in enumerate(got):
                        out[i] = v
                    return 0
                except BaseException as e:  # raised to the caller once the search stops
                    box["error"] = e
                    return _FB_EINTR

            fn = _RIDE_LIMIT_EVAL(evaluate)
            ncurves = len(values) * len(sys_ids)
            curves = (_RideLimitCurve * max(1, ncurves))()
            err = _Err()
            rc = _lib.fb_study_ride_limit(ncurves, ctypes.byref(opts), fn, None, curves, None,
                                          ctypes.byref(err))
            if "error" in box:
                raise box["error"]
            _check(rc, err)
            rows = []
            for c in range(ncurves):
                r = curves[c]
                found = r.status == 0
                rows.append(RideLimit(
                    values[c % len(values)], _SYSTEM_NAMES[sys_ids[c // len(values)]],
                    _RIDE_LIMIT_STATUS[r.status], r.speed * 3.6 if found else None,
                    r.metric_over if r.status == 1 else r.metric,
                    r.speed_over * 3.6 if found else None, r.metric_over if found else None,
                    r.nruns, errors.get(c)))
            return rows

        return _until_done(work)

    def simulation(self, system, progress=None):
        """A Simulation of one system of this scenario that the caller
        advances, reads and changes on the way (co-simulation); it keeps a
        copy of the scenario, which may be closed meanwhile. progress as
        run's, for the set-up (System 2's hull); Ctrl-C stops the set-up."""
        return Simulation(self, system, progress)

    def run_systems(self, systems=("rigid", "flexible")):
        """Runs each of systems; {name: Result}."""
        return {_SYSTEM_NAMES[_system(s)]: self.run(s) for s in systems}

    def modes(self, system, undamped=False, progress=None):
        """The modes of the vehicle at its static equilibrium (flexbond modes);
        undamped: with every damper removed (natural frequencies). A dense
        eigen-solve of the vehicle's states: refused (Error) beyond
        FB_DENSE_EIG_MAX of them (hull.fe.modes all on a fine mesh).
        progress as run's."""
        def use(v, _stop):
            modes = ctypes.POINTER(_Mode)()
            n, nstatic = ctypes.c_size_t(), ctypes.c_size_t()
            err = _Err()
            _check(_lib.fb_vehicle_linear_modes(v, int(bool(undamped)), ctypes.byref(modes),
                                                ctypes.byref(n), ctypes.byref(nstatic),
                                                ctypes.byref(err)), err)
            try:
                out = [Mode(complex(m.re, m.im), m.freq_hz, m.damping_ratio,
                            m.description.decode(errors="replace"))
                       for m in (modes[i] for i in range(n.value))]
            finally:
                _libc.free(ctypes.cast(modes, ctypes.c_void_p))
            return Modes(out, nstatic.value)

        return self._with_vehicle(system, use, progress=progress)

    def _in_call(self, system, body, hull_modes=0, progress=None):
        """body(s, sys_id, opts, reporter) for system of this scenario (s its
        handle, opts the fb_vehicle_opts with a _Reporter: the caller's
        progress, and the stop a Ctrl-C sets); in _until_done, so that
        Ctrl-C reaches the caller at once. An exception of progress is
        raised in place of the library's FB_EINTR. close() waits for the
        call."""
        sys_id = _system(system)
        with self._calls:  # open, and counted, at once: close() waits for the call
            s = self._handle()
            self._ncalls += 1

        def done():
            with self._calls:
                self._ncalls -= 1
                self._calls.notify_all()

        def work(stop):
            reporter = _Reporter(progress, stop, _SYSTEM_LABELS[sys_id])
            try:
                opts = _VehicleOpts()
                _lib.fb_vehicle_opts_default(ctypes.byref(opts))
                opts.progress_fn = reporter.stage_fn
                opts.hull_modes = hull_modes
                return body(s, sys_id, opts, reporter)
            except Error:
                if reporter.error is not None:
                    raise reporter.error from None
                raise
            finally:
                done()

        return _until_done(work, on_no_start=done)

    def _with_vehicle(self, system, use, hull_modes=0, progress=None):
        """use(vehicle, reporter) on system of this scenario, realised once
        (_in_call)."""
        def body(s, sys_id, opts, reporter):
            v = ctypes.c_void_p()
            err = _Err()
            _check_about(s, _lib.fb_vehicle_new(s, sys_id, ctypes.byref(opts), ctypes.byref(v),
                                                ctypes.byref(err)), err, self._data_name)
            try:
                return use(v, reporter)
            finally:
                _lib.fb_vehicle_free(ctypes.byref(v))

        return self._in_call(system, body, hull_modes, progress)

    def _with_descriptor(self, system, use):
        """use(descriptor) of system's linear model (flexbond export)."""
        def on_vehicle(v, _stop):
            ds = ctypes.POINTER(_Descriptor)()
            err = _Err()
            _check(_lib.fb_vehicle_linearise(v, ctypes.byref(ds), ctypes.byref(err)), err)
            try:
                return use(ds)
            finally:
                _lib.fb_descriptor_free(ctypes.byref(ds))

        return self._with_vehicle(system, on_vehicle)

    def _with_freq(self, system, freq_hz, use, progress=None):
        """use(study) of system's frequency response at freq_hz (a contiguous
        float array; may be empty: the linear model alone), fb_study_freq."""
        def on_vehicle(v, _reporter):
            f = ctypes.c_void_p()
            err = _Err()
            _check(_lib.fb_study_freq_new(v, freq_hz.ctypes.data_as(_PDOUBLE), freq_hz.size,
                                          ctypes.byref(f), ctypes.byref(err)), err)
            try:
                return use(f)
            finally:
                _lib.fb_study_freq_free(ctypes.byref(f))

        return self._with_vehicle(system, on_vehicle, progress=progress)

    def freq_response(self, system, freq_hz, progress=None):
        """H(j omega) = C (j omega E - A)^-1 B from each track's road height to
        each output at freq_hz (Hz, >= 0), as flexbond freq computes it (the
        library's study layer, fb_study_freq): a FreqResponse. progress as
        run's."""
        f = numpy.ascontiguousarray(numpy.atleast_1d(numpy.asarray(freq_hz, dtype=float)))
        if f.ndim != 1:
            raise ValueError("flexbond: freq_hz must be one-dimensional")
        outs = self.outputs
        name = _SYSTEM_NAMES[_system(system)]
        return self._with_freq(system, f, lambda fr: _freq_response(name, outs, fr), progress)

    def freq(self, system, f_min=0.1, f_max=100.0, points=301, progress=None):
        """The frequency response as flexbond freq computes it with --f-min,
        --f-max and --points (its defaults): points frequencies from f_min
        to f_max (Hz) evenly spaced on a log scale, the ends exact. A
        FreqResponse: freq_systemN.csv's |H| (magnitude) and phase
        (phase_deg), and the largest |H| it prints (peaks)."""
        points = int(points)
        if not (0 < f_min < f_max) or not 2 <= points <= _FREQ_MAX_POINTS:
            raise ValueError("flexbond: freq needs 0 < f_min < f_max and 2 <= points <= %d"
                             % _FREQ_MAX_POINTS)
        f = numpy.empty(points)
        _lib.fb_study_freq_log_grid(float(f_min), float(f_max), points,
                                    f.ctypes.data_as(_PDOUBLE))
        return self.freq_response(system, f, progress=progress)

    def ride_psd(self, system, road_class=None, tracks="independent", progress=None):
        """The ride from an ISO 8608 road's spectrum, as flexbond freq computes
        it (--road-class, --tracks): the road of class road_class ("A" ..
        "H") over ISO 8608's band, or (None) the scenario's own ISO 8608
        road; its tracks "independent" (as the road generator makes them)
        or "identical". Each output's PSD from the frequency response and
        the road's PSD, its r.m.s. over the band and the driver's a_w,
        without a time run: a RidePSD. ValueError when there is no ISO 8608
        road. progress as run's."""
        if tracks not in ("independent", "identical"):
            raise ValueError("flexbond: tracks is 'independent' or 'identical', not %r"
                             % (tracks,))
        cls = b"\0"
        if road_class is not None:
            if not (isinstance(road_class, str) and len(road_class) == 1
                    and road_class.upper() in "ABCDEFGH"):
                raise ValueError("flexbond: road_class %r is not an ISO 8608 class A to H"
                                 % (road_class,))
            cls = road_class.encode()
        iso = _Iso8608()
        if not _lib.fb_study_ride_psd_iso8608(self._handle(), cls, ctypes.byref(iso)):
            raise ValueError("flexbond: the scenario's road is no ISO 8608 road: give "
                             "road_class")
        outs = self.outputs
        name = _SYSTEM_NAMES[_system(system)]

        def use(lin):
            r = ctypes.c_void_p()
            err = _Err()
            _check(_lib.fb_study_ride_psd_new(lin, ctypes.byref(iso), int(tracks == "identical"),
                                              ctypes.byref(r), ctypes.byref(err)), err)
            try:
                return _ride_psd(name, outs, r)
            finally:
                _lib.fb_study_ride_psd_free(ctypes.byref(r))

        return self._with_freq(system, numpy.empty(0), use, progress)

    def export(self, system):
        """The vehicle's linear descriptor model (flexbond export) as a Model."""
        outs = self.outputs
        name = _SYSTEM_NAMES[_system(system)]

        def use(ds):
            d = ds.contents
            rows = [[d.output_row[o], d.output_row[o] + 1] if d.output_is_product[o]
                    else [d.output_row[o]] for o in range(d.noutputs)]
            return Model(name, E=_sparse(d.E), A=_sparse(d.A), B=_sparse(d.B), f=_sparse(d.f),
                         C=_sparse(d.C), D=_sparse(d.D), nstates=d.nstates,
                         var_names=_strings(d.var_names, d.n),
                         input_names=_strings(d.input_names, d.ninputs),
                         output_names=[n for n, _ in outs],
                         output_units=[unit for _, unit in outs],
                         output_rows=rows, linearised=bool(d.linearised))

        return self._with_descriptor(system, use)

    def export_fmu(self, path, system="flexible", road="scenario", parameters=(), t_end=0.0,
                   model_identifier=None):
        """The vehicle as an FMI 3.0 FMU at path (flexbond fmu, docs/fmi.md):
        Co-Simulation and Model Exchange, the scenario file with this
        Scenario's overrides fixed in it. road: "scenario" or "inputs" (each
        wheel's road height and rate as inputs); parameters: scenario keys
        made tunable; t_end: the longest run (0: the scenario's). Returns a
        dict: model_identifier, nstates, ninputs, noutputs, nparameters,
        nindicators, nlibraries, bytes. A scenario from data (from_dict) has
        no file to package: ValueError."""
        if self._text is not None:
            raise ValueError("flexbond: export_fmu needs a scenario loaded from a file")
        if road not in ("scenario", "inputs"):
            raise ValueError("flexbond: road is 'scenario' or 'inputs', not %r" % (road,))
        keys = [_c_text(k, "parameter") for k in parameters]
        ov, n = _overrides(self.overrides.items())
        o = _FmuOpts(system=_system(system), road_inputs=int(road == "inputs"),
                     parameters=(ctypes.c_char_p * max(1, len(keys)))(*keys),
                     nparameters=len(keys), overrides=ov, noverrides=n, t_end=float(t_end),
                     model_identifier=(_c_text(model_identifier, "model_identifier")
                                       if model_identifier else None))
        info, err = _FmuInfo(), _Err()
        _check(_lib.fb_fmu_export(_c_text(self.path, "path"), ctypes.byref(o),
                                  _c_text(os.fspath(path), "path"), ctypes.byref(info),
                                  ctypes.byref(err)), err)
        out = {n: getattr(info, n) for n, _ in _FmuInfo._fields_[1:]}
        out["model_identifier"] = info.model_identifier.decode()
        return out

    def __repr__(self):
        return "<flexbond.Scenario %s>" % self.path


# ---- Stepping.

class ModelFile(_Closing):
    """A bond-graph model file (docs/model-format.md) loaded and checked as
    flexbond sim reads it; Error at its file, line and key when it is wrong.
    name is its model's name; warnings the load's warnings (the messages
    flexbond sim prints and goes on). close() frees it (also done by the
    garbage collector and by a with block)."""

    def __init__(self, path):
        self._m = ctypes.c_void_p()
        err = _Err()
        _check(_lib.fb_model_load(_c_text(os.fspath(path), "path"), ctypes.byref(self._m),
                                  ctypes.byref(err)), err)
        self.name = _lib.fb_model_name(self._m).decode()
        self.warnings = [_lib.fb_model_warning(self._m, i).contents.msg.decode(
            errors="replace") for i in range(_lib.fb_model_nwarnings(self._m))]

    def simulate(self, t_end=None, rtol=None, sample_rate=None):
        """The model run as flexbond sim runs it, from its simulation.initial
        state, with its file's solver settings or t_end (s), rtol and
        sample_rate (Hz) instead (--t-end, --rtol, --sample-rate): a Result
        with t and each probe, probes.csv's columns. The call holds the
        interpreter's thread until the run ends."""
        if not self._m:
            raise ValueError("flexbond: the model file is closed")
        given = [0.0 if v is None else float(v) for v in (t_end, rtol, sample_rate)]
        for name, v in zip(("t_end", "rtol", "sample_rate"), given):
            if not v >= 0:  # also NaN; 0 would mean "the file's"
                raise ValueError("flexbond: %s must be > 0 (got %r)" % (name, v))
        opts = _lib.fb_model_sim_opts_with(self._m, *given)
        ms, res, err = ctypes.c_void_p(), ctypes.c_void_p(), _Err()
        try:
            _check(_lib.fb_model_sim_new(self._m, ctypes.byref(ms), ctypes.byref(err)), err)
            _check(_lib.fb_model_sim_run(ms, ctypes.byref(opts), ctypes.byref(res),
                                         ctypes.byref(err)), err)
            return _result(res, self.name)
        finally:
            _lib.fb_result_free(ctypes.byref(res))
            _lib.fb_model_sim_free(ctypes.byref(ms))

    def eigenvalues(self):
        """The eigenvalues of the model's state equations linearised at its
        graph's initial state and start time, as flexbond eig lists them
        (fb_bd_eigen_new): Eigenvalues."""
        if not self._m:
            raise ValueError("flexbond: the model file is closed")
        opts = _lib.fb_model_sim_opts(self._m).contents
        return _eigenvalues(_lib.fb_model_graph(self._m), opts.t_start, opts.x0,
                            "eigenvalues of " + self.name,
                            lambda err: _lib.fb_model_blame(self._m, ctypes.byref(err)))

    def close(self):
        if self._m:
            _lib.fb_model_free(ctypes.byref(self._m))

    def __repr__(self):
        return "<flexbond.ModelFile %s>" % self.name


class Simulation(_Closing):
    """One system of a scenario simulated step by step, as an FMI
    co-simulation slave (fmi2DoStep) or a Chrono system (DoStepDynamics) is:
    advance(t) integrates to time t exactly, outputs reads every output
    there, set(...) changes an input or a value of the scenario, and the
    next advance goes on from there (flexbond/vehicle.h, fb_vehicle_stepper).
    Made by Scenario.simulation(system). It integrates as Scenario.run
    does; cut at the caller's times, its outputs agree with the run's
    within the scenario's tolerances.

    What can change, at the current time, the integration restarting there
    from the current state:
      - an input (inputs: {name: value}), held until changed (zero-order
        hold): "load_force", a vertical force on the load (N, up positive),
        shared by the load points as the payload's weight is;
      - any value of the scenario (set({key: value}) with the keys of
        Scenario's overrides, or set_scenario(other)): the vehicle is
        realised again and goes on from the current state, which must mean
        the same there (no corner, mount or hull coordinate added or
        removed: Error otherwise). The road is a function of time: a new
        speed or bump moves it under the wheels from now on.

    advance runs in the calling thread: a Ctrl-C is seen when it returns,
    so advance in steps that take a moment each."""

    def __init__(self, scenario, system, progress=None):
        self._st = ctypes.c_void_p()
        sys_id = _system(system)
        self.system = _SYSTEM_NAMES[sys_id]
        self._path, self._overrides = scenario.path, scenario.overrides

        def body(s, sys_id, opts, reporter):
            st = ctypes.c_void_p()
            err = _Err()
            _check_about(s, _lib.fb_vehicle_stepper_new(s, sys_id, ctypes.byref(opts),
                                                        ctypes.byref(st), ctypes.byref(err)),
                         err, scenario._data_name)
            if reporter.stop:  # the caller has gone: nobody will free it
                _lib.fb_vehicle_stepper_free(ctypes.byref(st))
            return st

        self._st = scenario._in_call(system, body, progress=progress)
        self._names()

    def _names(self):
        n = _lib.fb_vehicle_stepper_noutputs(self._st)
        self.names = [_lib.fb_vehicle_stepper_output_name(self._st, k).decode()
                      for k in range(n)]
        self.units = {name: _lib.fb_vehicle_stepper_output_unit(self._st, k).decode()
                      for k, name in enumerate(self.names)}
        self._index = {name: k for k, name in enumerate(self.names)}
        self._y = numpy.empty(max(1, n))

    def _handle(self):
        if not self._st:
            raise ValueError("flexbond: the simulation is closed")
        return self._st

    @property
    def time(self):
        """The time reached, s."""
        return _lib.fb_vehicle_stepper_time(self._handle())

    def advance(self, t):
        """Integrates to time t (s), from the current time to the scenario's
        t_end; returns self. Error if t is outside that range or the
        integration fails (the simulation cannot go on after a failure)."""
        err = _Err()
        _check(_lib.fb_vehicle_stepper_advance(self._handle(), float(t), ctypes.byref(err)), err)
        return self

    def step(self, dt):
        """advance(time + dt)."""
        return self.advance(self.time + float(dt))

    @property
    def outputs(self):
        """Every output at the current time: {name: value} in the order of
        Scenario.run's columns after t (the scenario's outputs, then each
        tire's contact_force_<CORNER>), SI units (units: {name: unit})."""
        err = _Err()
        _check(_lib.fb_vehicle_stepper_outputs(self._handle(), self._y.ctypes.data_as(_PDOUBLE),
                                               ctypes.byref(err)), err)
        return dict(zip(self.names, self._y.tolist()))

    def output(self, name):
        """One output at the current time."""
        if name not in self._index:
            raise KeyError("flexbond: no output %r; the outputs are %s"
                           % (name, ", ".join(self.names)))
        return self.outputs[name]

    __getitem__ = output

    @property
    def inputs(self):
        """The inputs and the values they hold: {name: value}."""
        st = self._handle()
        out, i = {}, 0
        while _lib.fb_vehicle_input_name(i) is not None:
            out[_lib.fb_vehicle_input_name(i).decode()] = _lib.fb_vehicle_stepper_input(st, i)
            i += 1
        return out

    def set_input(self, name, value):
        """Holds input name at value from the current time on."""
        err = _Err()
        _check(_lib.fb_vehicle_stepper_set_input(self._handle(), _c_text(name, "input name"),
                                                 float(value), ctypes.byref(err)), err)

    def set_scenario(self, scenario):
        """Goes on with scenario (a Scenario of the same kind of vehicle)
        from the current time and state, the inputs held as they are."""
        with scenario._calls:
            s = scenario._handle()
            err = _Err()
            rc = _lib.fb_vehicle_stepper_set_scenario(self._handle(), s, ctypes.byref(err))
            _check_about(s, rc, err, scenario._data_name)
        self._path, self._overrides = scenario.path, scenario.overrides
        self._names()

    def set(self, changes):
        """Changes {name: value} at the current time: each name an input
        (held at value) or a key of the scenario file as Scenario's
        overrides take it ("speed_kmh", "suspensions.axles[0].spring_k"),
        all of those applied at once on top of the scenario's own overrides
        (a scenario read from a file: Scenario.from_dict's have none; give
        set_scenario the changed description instead)."""
        inputs = self.inputs
        held = {k: v for k, v in changes.items() if k in inputs}
        values = {k: v for k, v in changes.items() if k not in inputs}
        if values:
            if self._overrides is None:
                raise ValueError("flexbond: %s is no input (%s), and a scenario made from data "
                                 "takes its changes through set_scenario"
                                 % (", ".join(map(repr, values)), ", ".join(inputs)))
            merged = dict(self._overrides)
            merged.update(values)
            with Scenario(self._path, overrides=merged) as changed:
                self.set_scenario(changed)
        for name, value in held.items():
            self.set_input(name, value)

    def close(self):
        """Frees the simulation (also done when it is garbage-collected)."""
        if getattr(self, "_st", None):
            _lib.fb_vehicle_stepper_free(ctypes.byref(self._st))

    def __repr__(self):
        return "<flexbond.Simulation %s at t = %g s>" % (
            self.system, self.time if self._st else float("nan"))
