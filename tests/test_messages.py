"""Warnings as data (tmm_cli/messages): the English catalogue renders exactly the texts
results.json has always held, every language's catalogue has every code with the same
placeholders, every code a stage emits is catalogued, the stage modules hold no language
literal, and the Russian and Ukrainian texts leave no English phrase."""
from __future__ import annotations

import ast
import pickle
import re
import string
from pathlib import Path

import pytest

from tmm_cli import messages
from tmm_cli.messages import LANGS, PLAIN, Message, as_dict, catalogue, localize, render, render_list

ROOT = Path(__file__).resolve().parents[1]
PKG = ROOT / "tmm_cli"
STAGES = ("linkage", "cam", "gears", "dof2")       # the stage packages (no language literal there)
OTHERS = [lang for lang in LANGS if lang != "en"]

# (code, params, the English text as the stages wrote it before the catalogue existed:
# each text below is the output of the former f-string of the stage for these params)
ENGLISH = [
    ('input.speed_plain', {'field': 'drive.speed', 'value': 60.0, 'rpm': 572.9577951308232},
     "drive.speed: the plain number 60 is read as 60 rad/s (573 rpm); if you meant rpm, write '60 rpm'"),
    ('input.length_plain', {'field': 'mechanism.links[0].length', 'value': 100.0},
     "mechanism.links[0].length: the plain number 100 is read as 100 m; if you meant millimetres, write '100 mm'"),
    ('structure.idle_link', {'link': 'rod'},
     "link 'rod' has a single pair: an idle (local) degree of freedom"),
    ('structure.passive', {'links': ['rod', 'slider'], 'pairs': 7, 'freedoms': 6, 'extra': 2},
     'links rod, slider carry 7 pairs for 6 freedoms: 2 passive (redundant) constraint(s)'),
    ('kinematics.singular_continuity', {'group': 'II(2,3)', 'links': ['rod', 'slider'], 'angles': [12.345679, 180.0, 360.0], 'delta': 0.001},
     "group II(2,3) (links rod, slider): the velocity equations are singular at crank angle(s) 12.346, 180, 0 deg (the group's links are collinear: a toggle or change point); velocities and accelerations there are the limit by continuity, or null where the values on either side differ (each position's warning says which)"),
    ('kinematics.closure_not_at_zero', {'group': 'II(2,3)', 'links': ['rod', 'slider'], 'phi': 37.25},
     'group II(2,3) (links rod, slider) does not assemble at crank angle 0 deg; its closure was chosen at 37.25 deg (assembly hints refer to 0 deg)'),
    ('kinematics.no_assembly_hints', {'group': 'II(2,3)', 'links': ['rod', 'slider']},
     'group II(2,3) (links rod, slider): no assembly hints; the closure with the highest mean y of its points was taken (give mechanism.assembly to choose another)'),
    ('kinematics.transmission_low', {'group': 'II(2,3)', 'links': ['rod', 'slider'], 'joint': 'B', 'gamma': 17.7528,
                                     'phi': 90.0, 'factor': 3.2804, 'recommended': 40.0, 'low': 20.0},
     'group II(2,3) (links rod, slider): the transmission angle falls to 17.8 deg at crank angle 90 deg (at its joint B); the force it transmits there grows as 1/sin gamma, to 3.3 times that at 90 deg. A lever mechanism is designed with at least 40 deg; tmm warns below 20 deg'),
    ('kinematics.transmission_dead', {'group': 'II(2,3)', 'links': ['rod', 'rocker'], 'joint': 'B', 'phi': 41.40962,
                                      'recommended': 40.0},
     'group II(2,3) (links rod, rocker) passes a dead point at crank angle 41.41 deg: its transmission angle is 0 there (at its joint B), and the forces in its joints have no bound. A lever mechanism is designed with a transmission angle of at least 40 deg'),
    ('kinematics.change_point', {'phi': 123.4567891234, 'group': 'II(2,3)', 'links': ['rod', 'slider'], 'near': 1.0, 'blowup': 10.0},
     "change point at crank angle 123.457 deg: group II(2,3) (links rod, slider): the velocity equations are singular there (the group's links are collinear, as in a four-bar on the Grashof limit s + l = p + q); the linkage may switch branch and its velocities and accelerations jump. Positions within 1 deg are marked near_singular; a value there more than 10 times its largest elsewhere in the cycle has no finite limit and is null"),
    ('kinematics.by_continuity', {'phi': 270.0, 'group': 'II(2,3)', 'links': ['block', 'rocker'], 'det': 3.67e-17, 'ill': 0.001, 'quantities': ['v B', 'ω rocker']},
     "crank angle 270 deg: group II(2,3) (links block, rocker) is ill-conditioned there (normalised determinant 3.7e-17, below 0.001); v B, ω rocker are given as the limit by continuity (extrapolated from the neighbouring positions of the same branch)"),
    ('kinematics.no_limit', {'phi': 180.0, 'group': 'II(2,3)', 'links': ['coupler', 'rocker'], 'det': 3.4e-08, 'ill': 0.001, 'quantities': ['v B', 'ω rocker']},
     "crank angle 180 deg: group II(2,3) (links coupler, rocker) is ill-conditioned there (normalised determinant 3.4e-08, below 0.001); v B, ω rocker have no limit by continuity (the values from either side differ: the linkage may switch branch) and are null"),
    ('positions.output_rests', {'link': 'slider', 'intervals': [[90.5, 269.5]], 'extreme': [98.0857, 0.0]},
     "the output 'slider' stands still over \u03c6 = 90.5\u2026269.5\u00b0 (its coordinate constant, as on the branch a "
     "change point folds it onto): its extreme positions there are no one angle, so the extremes taken (98.086, 0 "
     "deg), the working and idle strokes, K and theta are one choice, not the mechanism's"),
    ('positions.quick_working', {'working': 'backward', 'link': 'rocker', 'K': 0.8781, 'slow': 'forward'},
     "positions.working = backward makes the working stroke of 'rocker' the quick one (K = 0.878 < 1): the slow "
     "stroke is the forward one; write working: forward if the working stroke is meant to be the slow one"),
    ('inertia.massless', {'links': ['coupler', 'block']},
     "inertia is taken into account, but links coupler, block have no mass (mass not given or 0): no inertia "
     "force acts on them"),
    ('inertia.massless_flywheel', {'links': ['coupler']},
     "inertia is taken into account, but links coupler have no mass (mass not given or 0): no inertia force "
     "acts on them and their mass adds nothing to the reduced moment of inertia"),
    ('kinetostatics.self_locking', {'position': 5, 'phi': 52.345669999999984, 'f_pin': 0.1, 'f_slide': 0.15, 'pin_radius': 0.01, 'balancing': 'moment'},
     'kinetostatics: position 5 (phi = 52.346 deg) is self-locking with friction f_pin = 0.1, f_slide = 0.15, pin radius 0.01 m: the friction loads grow without bound, no finite balancing moment'),
    ('kinetostatics.singular_balance', {'position': 5, 'phi': 52.345669999999984, 'link': 'crank', 'balancing': 'moment'},
     "kinetostatics: position 5 (phi = 52.346 deg) is singular for the balance link 'crank': no finite balancing moment"),
    ('kinetostatics.no_kinematics', {'position': 6, 'phi': 180.0, 'link': 'crank', 'balancing': 'moment'},
     "kinetostatics: position 6 (phi = 180 deg) is a singular or change point of the linkage (its velocities or accelerations have no limit by continuity there, or its groups' equilibrium equations are singular): no balancing moment or reactions"),
    ('kinetostatics.self_locking', {'position': 5, 'phi': 52.345669999999984, 'f_pin': 0.1, 'f_slide': 0.15, 'pin_radius': 0.01, 'balancing': 'force'},
     'kinetostatics: position 5 (phi = 52.346 deg) is self-locking with friction f_pin = 0.1, f_slide = 0.15, pin radius 0.01 m: the friction loads grow without bound, no finite balancing force'),
    ('kinetostatics.singular_balance', {'position': 5, 'phi': 52.345669999999984, 'link': 'crank', 'balancing': 'force'},
     "kinetostatics: position 5 (phi = 52.346 deg) is singular for the balance link 'crank': no finite balancing force"),
    ('flywheel.not_needed_exceeds', {'J_const': 0.123456789, 'J_needed': 0.0987654321, 'delta': 0.05, 'method': 'energy-mass'},
     "no flywheel is needed: the machine's own constant reduced inertia 0.123457 kg*m^2 exceeds the 0.0987654 kg*m^2 needed for delta = 0.05 (energy-mass); J = 0"),
    ('flywheel.not_needed_no_work', {},
     'no flywheel is needed: the loads do no work over any part of the cycle and the reduced inertia is constant, so the speed does not fluctuate; J = 0'),
    ('flywheel.delta_unusual', {'delta': 0.001, 'inverse': 1000.0, 'lo': 5.0, 'hi': 300.0},
     "the coefficient of speed fluctuation delta = 0.001 (1/1000) is outside the usual 1/5...1/300 of machines "
     "(pumps 1/5-1/30, machine tools 1/20-1/50, compressors 1/50-1/100, generators 1/100-1/300): the flywheel is "
     "sized for it"),
    ('flywheel.not_needed_equal', {'J_const': 0.123456789, 'J_needed': 0.0987654321, 'delta': 0.05, 'method': 'energy-mass'},
     "no flywheel is needed: the machine's own constant reduced inertia 0.123457 kg*m^2 equals the 0.0987654 kg*m^2 needed for delta = 0.05 (energy-mass); J = 0"),
    ('flywheel.net_positive_work', {'M': -12.3456789},
     'the given loads do net positive work over the cycle: the constant driving moment is negative (-12.3457 N*m); is `constant: resistance` (an engine) meant?'),
    ('flywheel.net_negative_work', {'M': -12.3456789},
     'the given loads do net negative work over the cycle: the constant resistance moment is negative (-12.3457 N*m); is `constant: driving` (a motor-driven machine) meant?'),
    ('flywheel.coarse_resolution', {'resolution': 24, 'rel': 3.456e-05, 'doubled': 48, 'target': 1e-06},
     'flywheel: at resolution 24 J_n differs by 3.5e-05 (relative) from its value at 48 positions, more than 1e-06; raise `flywheel.resolution`'),
    ('flywheel.resolution_error', {'resolution': 24, 'percent': 2.34},
     'flywheel: at resolution 24 J differs by 2.3 % from the converged value; raise `flywheel.resolution`'),
    ('flywheel.rim_speed_steel', {'v': 123.456, 'limit': 100.0},
     'flywheel rim speed 123.5 m/s exceeds about 100 m/s, the usual limit even for steel flywheels: move the flywheel to a faster shaft or change its shape'),
    ('flywheel.rim_speed_cast_iron', {'v': 123.456, 'limit': 30.0},
     'flywheel rim speed 123.5 m/s exceeds about 30 m/s, the usual limit for cast iron: make it of steel'),
    ('cam.swing_auto', {'swing': 'against', 'r0': 20.299999999999997, 'other': 'with', 'r0_other': 21.4868},
     'swing auto: the rocker turns against the cam on the rise (r0 = 20.300 mm; with: 21.487 mm)'),
    ('cam.roller_rho', {'roller': 12.0, 'limit': 9.87648},
     'roller radius 12.000 mm exceeds 0.8 rho_min = 9.876 mm (course rule)'),
    ('cam.pressure_high', {'angle': 89.0, 'usual': 30.0, 'high': 60.0, 'force': 57.3},
     "allowed pressure angle 89 deg is far above the usual 30 deg for this follower: past 60 deg the cam pushes with "
     "57.3 times the force the follower's motion takes, the follower can jam, and the smallest cam is a sliver"),
    ('cam.roller_r0', {'roller': 12.0, 'limit': 10.149999999999999},
     'roller radius 12.000 mm exceeds 0.5 r0 = 10.150 mm (course rule)'),
    ('cam.rigid_impact', {'phi': 123.45678, 'where': 'rise/far_dwell'},
     'rigid impact (jump of velocity, infinite acceleration) at phi = 123.5 deg (rise/far_dwell)'),
    ('cam.soft_impact', {'phi': 123.45678, 'where': 'rise/far_dwell'},
     'soft impact (finite jump of acceleration) at phi = 123.5 deg (rise/far_dwell)'),
    ('cam.profile_corners_knife', {'phis': [0.0, 120.0]},
     'the profile has corners where the velocity jumps (phi = 0, 120 deg): the knife edge rides over sharp edges '
     'there; rho_min refers to the smooth parts'),
    ('cam.profile_corners', {'phis': [0.0, 120.00001]},
     'the pitch profile has corners where the velocity jumps (phi = 0, 120 deg): the working profile has sharp edges there; rho_min and the roller rule refer to the smooth parts'),
    ('gears.no_involute_above_tip', {'wheel': 1, 'z': 7, 'x': -0.5, 'r_start': 12.345678900000001, 'r_tip': 11.9},
     'gears: wheel 1 (z = 7, x = -0.5) has no involute flank: its involute would begin at r = 12.3457 mm, above the tip r = 11.9 mm; the pair cannot mesh properly (s_a and eps_alpha are formal values)'),
    ('gears.no_involute_pointed_fillet', {'wheel': 1, 'z': 7, 'x': -0.5, 'r_start': 12.345678900000001, 'r_tip': 11.9},
     'gears: wheel 1 (z = 7, x = -0.5) has no involute flank: its involute would begin at r = 12.3457 mm, above the tip r = 11.9 mm (pointed on the fillet); the pair cannot mesh properly (s_a and eps_alpha are formal values)'),
    ('gears.no_involute_inside_base', {'wheel': 1, 'z': 7, 'x': -0.5},
     'gears: wheel 1 (z = 7, x = -0.5) has no involute flank: its tip circle lies inside the base circle; the pair cannot mesh properly (s_a and eps_alpha are formal values)'),
    ('gears.undercut', {'wheel': 2, 'z': 15, 'x': 0.0, 'x_min': 0.11764705882},
     'gears: wheel 2 (z = 15) is undercut: x2 = 0 < x_min = 0.1176'),
    ('gears.tip_thin', {'wheel': 2, 'sa': 0.12345600000000001, 'k': 0.25, 'limit': 1.0},
     'gears: wheel 2 tip is too thin: sa = 0.1235 mm < 0.25 m = 1 mm'),
    ('gears.tip_pointed', {'wheel': 2, 'sa': -0.1, 'k': 0.25, 'limit': 1.0},
     'gears: wheel 2 tip is too thin: sa = -0.1 mm < 0.25 m = 1 mm (pointed tooth)'),
    ('gears.interference', {'other': 1, 'wheel': 2, 'rho_p': 1.23456, 'rho_l': 2.3456},
     'gears: interference: the tip of wheel 1 reaches wheel 2 below the start of its involute (rho_p = 1.235 mm < rho_l = 2.346 mm)'),
    ('gears.eps_pointed', {'eps': 1.0105, 'wheel': 2, 'r_point': 12.34, 'ra': 13.5, 'eps_cut': 0.8545},
     'eps_alpha = 1.01 by the formula is formal: the tooth of wheel 2 comes to a point at r = 12.34 mm, below '
     'its tip circle r_a = 13.5 mm, and meshes only up to it; with the tip there eps_alpha = 0.8545'),
    ('cam.phase_coarse', {'phase': 'rise', 'angle': 0.5, 'step': 1.0, 'steps': 10},
     'cam: the rise spans 0.5 deg, fewer than 10 steps of the 1 deg grid of the motion and profile tables, the '
     'diagrams and cam_profile.csv/.dxf: they show it coarsely, or not at all below one step (r0, rho_min and the '
     'pressure angles are found on the laws themselves)'),
    ('gears.eps_formal', {'eps': 1.2427, 'b': 14.67, 'n': 8.89},
     "eps_alpha = 1.243 by the formula is formal: with interference a tip works off the mate's involute, so part of "
     "the active line B1B2 = 14.670 mm (N1N2 = 8.890 mm) is no conjugate action and the teeth do not mesh "
     "continuously along it"),
    ('gears.contact_ratio_course', {'eps': 1.0567891, 'limit': 1.2},
     'gears: contact ratio eps_alpha = 1.057 < 1.2 (course minimum)'),
    ('gears.contact_ratio_absolute', {'eps': 1.05, 'limit': 1.1},
     'gears: contact ratio eps_alpha = 1.05 < 1.1 (absolute minimum)'),
    ('gears.contact_ratio_broken', {'eps': 0.95, 'limit': 1.1},
     'gears: contact ratio eps_alpha = 0.95 < 1.1 (absolute minimum); the mesh is not continuous (eps < 1)'),
    ('gears.no_admissible_shifts', {'rule': 'equal_sliding', 'x1': 0.123456, 'x2': -0.5},
     'gears: no shifts satisfy every check (rule equal_sliding gives x = [0.1235, -0.5000], kept)'),
    ('gears.shifts_outside_contour', {'rule': 'equal_sliding', 'x1': 0.123456, 'x2': -0.5, 'nx1': 0.2, 'nx2': -0.41},
     'gears: rule equal_sliding gives x = [0.1235, -0.5000] outside the blocking contour; the nearest admissible point [0.2000, -0.4100] is used'),
    ('planetary.plan_ratio', {'plan': 4.0000001, 'willis': 4.0},
     "planetary: velocity plan ratio 4 differs from Willis' 4"),
    ('drive_train.undercut', {'stage': 0, 'z': 12, 'limit': 17},
     'drive_train: stage 0: a wheel of 12 teeth < 17 is undercut without a profile shift'),
    ('drive_train.ratio_missed', {'ratio': 12.3456789, 'required': 12.5, 'error': -0.0123456, 'tolerance': 0.01},
     "drive_train: the train's ratio 12.3457 misses the required 12.5 by -1.235% (tolerance 0.01)"),
    ('drive_train.output_sense', {'output': 'cw', 'drive': 'ccw'},
     'drive_train: the output shaft turns cw, the drive link ccw'),
    ('dof2.no_impact', {'phi': 270.0, 't': 0.5},
     'dof2: the rotor does not reach the impact angle phi = 270 deg within t = 0.5 s'),
    ('dof2.energy_balance', {'rel': 1.234e-05},
     'dof2: the energy balance is off by 1.2e-05 of the energy (integration accuracy)'),
    ('dof2.rotor_reverses', {},
     'dof2: the rotor reverses its direction of rotation'),
    # tmm batch: the message column (the former f-strings of tmm_cli/batch.py)
    ('batch.nobody_answered', {}, 'nobody answered this variant'),
    ('batch.no_answers_to_check', {}, 'no answers to check'),
    ('batch.results_in', {'folder': 'press-2'}, ' (results in press-2/)'),
    ('form.renamed', {'file': 'src/V1.yaml', 'name': 'V1-2'},
     'note: src/V1.yaml: its form and key are V1-2.form.yaml and V1-2.key.yaml (a file name every system '
     'takes, one per task)'),
    ('batch.set_no_answers', {'file': 's01.yaml'}, 'no answers in s01.yaml'),
    ('batch.set_not_ok', {'status': 'outside', 'paths': ['flywheel.J', 'positions.K']},
     'outside: flywheel.J, positions.K'),
    ('batch.set_not_ok_more', {'status': 'missing', 'paths': ['a.b', 'c.d']}, 'missing: a.b, c.d ...'),
    ('batch.no_task_of_variant', {'variant': 77}, 'answers for variant 77: no task of this variant'),
    ('batch.no_task_of_name', {'file': 'ghost.yaml'}, "answers file 'ghost.yaml': no task of this name or variant"),
    ('batch.out_of_memory', {'limit': 4096},
     'out of memory: the variant needs more than the --memory limit of 4096 MB'),
    ('batch.memory_unlimited', {'limit': 4096},
     "note: --memory 4096 is not enforced here (no RLIMIT_AS and no `psutil` to read the workers' memory); "
     "install `psutil`"),
    ('batch.no_report', {'error': 'PicklingError'}, 'internal error: the worker could not report: PicklingError'),
    ('batch.worker_killed', {'signal': 'SIGKILL'},
     'the worker died of SIGKILL (killed: e.g. by the out-of-memory killer)'),
    ('batch.worker_signal', {'signal': 'SIGSEGV'}, 'the worker died of SIGSEGV'),
    ('batch.worker_exit', {'code': 1, 'limit': None},
     'the worker exited with code 1 without a result (memory limit None MB?)'),
    ('batch.timeout', {'timeout': 4.0}, 'time limit exceeded: the variant ran longer than --timeout 4 s'),
    ('batch.stage_failed', {'stage': 'cam', 'where': {'code': 'text', 'params': {'text': ''}, 'text': ''},
                            'message': {'code': 'cam.fail.stroke', 'params': {}, 'text': 'the stroke must be positive'}},
     "stage 'cam' failed: the stroke must be positive"),
    ('batch.at_angle', {'angle': 123.4567891}, ' at crank angle 123.457 deg'),
    ('batch.not_a_task', {'file': 'src/v1.yaml', 'reason': {'code': 'batch.directory', 'params': {}, 'text': 'x'}},
     'src/v1.yaml: a directory, not a task file'),
    ('batch.dangling_link', {}, 'a dangling symbolic link'),
    ('batch.no_such_file', {}, 'no such file'),
    ('batch.unreadable', {'error': 'Permission denied'}, 'cannot be read: Permission denied'),
    ('batch.directory', {}, 'a directory, not a task file'),
    ('batch.fifo', {}, 'a FIFO (named pipe), not a task file'),
    ('batch.not_regular', {}, 'not a regular file'),
    ('output.file_in_use', {}, 'the file is open in another program (a PDF viewer, a spreadsheet) or protected; '
                               'close it and run again'),
    ('output.earlier_run', {'folder': 'out/v1/', 'when': '2026-12-06 15:31'},
     'note: out/v1/ still holds the outputs of an earlier run (2026-12-06 15:31): they are not of the task '
     'file as it is now'),
    ('study.nothing_to_sweep', {'sections': ['differential']},
     'nothing to sweep: `tmm study` sweeps the settings of a linkage (`mechanism` or `synthesis`: its curves, '
     '`flywheel` and `kinetostatics`), `cam`, `gears`, `planetary` and `dof2`, and this task has none of them '
     '(its sections: differential); study.json and study.html are not written'),
    # structure: a linkage the crank cannot drive (the former f-strings of linkage/structure.py)
    ('structure.fail.reasons', {'reasons': [
        {'code': 'structure.fail.lonely_point', 'params': {'point': 'C', 'link': 'rod', 'hint': {
            'code': 'structure.fail.point_hint', 'params': {'point': 'B'}, 'text': 'x'}}, 'text': 'x'},
        {'code': 'structure.fail.inputs', 'params': {'W': 3, 'n': 3, 'p5': 3, 'p4': 0}, 'text': 'x'},
        {'code': 'structure.fail.idle', 'params': {'links': ['rod', 'ram']}, 'text': 'x'}]},
     "point C is used by rod only: a pair needs two links — did you mean B?; W = 3: by Chebyshev's formula "
     "W = 3*3 - 2*3 - 0 = 3; one crank cannot define the motion (n = 3, p5 = 3); the linkage needs 3 inputs; "
     "idle degree(s) of freedom: link(s) rod, ram with a single pair"),
    ('structure.fail.lonely_point', {'point': 'E', 'link': 'link4', 'hint': {'code': 'text', 'params': {'text': ''},
                                                                          'text': ''}},
     'point E is used by link4 only: a pair needs two links'),
    ('structure.fail.point_hint', {'point': 'C'}, ' — did you mean C?'),
    ('structure.fail.rigid', {'W': 0, 'n': 4, 'p5': 6, 'p4': 0},
     "W = 0: by Chebyshev's formula W = 3n - 2p5 - p4 = 3*4 - 2*6 - 0 = 0, the linkage is a rigid structure "
     "(n = 4 moving links, p5 = 6 lower pairs)"),
    ('structure.fail.over_constrained', {'W': -1, 'n': 3, 'p5': 5, 'p4': 0},
     "W = -1: by Chebyshev's formula W = 3n - 2p5 - p4 = 3*3 - 2*5 - 0 = -1, the linkage is an over-constrained "
     "structure (n = 3 moving links, p5 = 5 lower pairs)"),
    ('structure.fail.special_dimensions', {},
     'it can move only thanks to special dimensions (passive constraints); remove the redundant link or pair'),
    ('structure.fail.inputs', {'W': 2, 'n': 4, 'p5': 5, 'p4': 0},
     "W = 2: by Chebyshev's formula W = 3*4 - 2*5 - 0 = 2; one crank cannot define the motion (n = 4, p5 = 5); "
     "the linkage needs 2 inputs"),
    ('structure.fail.idle', {'links': ['rod']}, 'idle degree(s) of freedom: link(s) rod with a single pair'),
    ('structure.fail.no_groups', {'links': ['a', 'b'], 'crank': 'crank'},
     "links a, b cannot be split into Assur groups attached to the crank 'crank' (passive constraints and idle "
     "freedoms cancel in Chebyshev's formula?)"),
    # the task model's own checks (the former texts of tmm_cli/task.py)
    ('input.guide_kind', {},
     'a guide needs `through` (fixed guide) or `link` (moving guide)'),
    ('input.guide_both', {},
     'a guide is either fixed (`through`) or on a link (`link`), not both'),
    ('input.guide_angle', {},
     'a fixed guide needs `angle` (deg from +x)'),
    ('input.bar_points', {'n': 3},
     'a bar has exactly two points [P, Q], got 3'),
    ('input.bar_same_points', {},
     'the two points of a bar must differ'),
    ('input.link_kind', {},
     'a link needs `points: [P, Q]` (bar) or `slider: P` (block)'),
    ('input.link_both', {},
     'a link is either a bar (`points`) or a slider (`slider`), not both'),
    ('input.bar_length', {},
     'a bar link needs `length`'),
    ('input.slider_guide', {},
     'a slider needs a `guide`'),
    ('input.slider_length', {},
     'a slider has no `length`'),
    ('input.no_links', {},
     'at least one link is needed'),
    ('input.no_speed', {},
     "required field is missing: the crank's `speed`, or the output's `mean_output_speed` or `working_stroke_speed`"),
    ('input.speed_one', {'given': ['speed', 'mean_output_speed']},
     "give exactly one of `speed` (the crank's), `mean_output_speed` or `working_stroke_speed` (the output's); got speed, mean_output_speed"),
    ('input.diagram_axis', {},
     'a diagram needs exactly one abscissa: `s` (relative stroke) or `phi` (crank angle)'),
    ('input.diagram_short', {},
     'a diagram needs at least two points'),
    ('input.diagram_order', {},
     'the abscissa must be non-decreasing'),
    ('input.diagram_s', {},
     'relative stroke `s` must lie in [0, 1]'),
    ('input.load_what', {},
     'a load needs exactly one of `magnitude`, `diagram` (a force) or `moment` (a couple)'),
    ('input.load_what_got', {'given': ['magnitude', 'moment']},
     'a load needs exactly one of `magnitude`, `diagram` (a force) or `moment` (a couple); got magnitude, moment'),
    ('input.friction_both', {},
     'give `f` (both kinds of pair) or `f_pin` / `f_slide`, not both'),
    ('input.friction_none', {},
     'give the friction coefficient `f`, or `f_pin` and/or `f_slide`'),
    ('input.phases_over', {'used': 370.5},
     'rise + far_dwell + return = 370.5 deg exceeds 360'),
    ('input.phases_sum', {'total': 350.0},
     'phases sum to 350 deg, not 360'),
    ('input.z_min', {},
     'tooth numbers must be at least 5'),
    ('input.needs_drive', {},
     'a `mechanism` needs a `drive` section (link, speed, direction)'),
    ('input.needs_mechanism', {'sections': ['drive', 'loads']},
     'section(s) drive, loads need a `mechanism`'),
    ('input.flywheel_loads', {},
     '`flywheel` needs `loads` (the forces whose work it evens out)'),
    # a student's answers file (the former texts of tmm_cli/check.py)
    ('answers.not_answers_file', {},
     'not an answers file (a YAML file with an `answers:` mapping of result paths to values)'),
    ('answers.unknown_key', {'key': 'anwsers'},
     "unknown key 'anwsers'; an answers file holds `answers`, `tolerance`, `student` and `variant`"),
    ('answers.invalid', {'reason': {'code': 'input.number_not_number', 'params': {'text': 'abc'}, 'text': 'x'}},
     "invalid answer: 'abc' is not a number"),
    ('batch.set_statuses', {'parts': [{'code': 'batch.set_not_ok', 'params': {'status': 'outside', 'paths': ['a']},
                                       'text': 'outside: a'},
                                      {'code': 'batch.set_not_ok', 'params': {'status': 'invalid', 'paths': ['b']},
                                       'text': 'invalid: b'}]},
     "outside: a; invalid: b"),
    ('batch.answers_outside', {'count': 2, 'variants': ['07', '08']},
     "answers for variants outside the tasks given (in their folder) not graded: 2 (07, 08)"),
    ('answers.other_variants', {'count': 12, 'variants': ['1', '10', '11', '2', '3', '4', '5', '6'], 'more': ', ...'},
     '12 answer set(s) of other variants (1, 10, 11, 2, 3, 4, 5, 6, ...) left for their own tasks'),
    ('answers.other_variant_file', {'file': 'form7.yaml', 'variant': '7', 'task': '3'},
     'form7.yaml holds answers for variant 7; the task is variant 3'),
    ('answers.none_for_variant', {'variant': '3', 'source': 'group21.csv'}, 'no answers for variant 3 in group21.csv'),
    ('answers.repeat', {'file': 'a.yaml', 'student': 'Ivanov', 'others': ['b.yaml']},
     "a.yaml: another submission of Ivanov for this variant: b.yaml"),
    ('answers.older_dropped', {'file': 'a.yaml', 'student': 'Ivanov', 'newer': 'b.yaml'},
     "a.yaml: an older submission of Ivanov for this variant, not graded (--latest: b.yaml is the newest)"),
    ('answers.tolerance_ignored', {'where': 's.yaml:3'},
     "s.yaml:3: the answers file's `tolerance` is ignored: answers are graded with the task's tolerances and "
     "--tolerance FILE"),
    ('answers.invalid_cell', {'where': 'a.csv:3', 'column': 'flywheel.J',
                              'reason': {'code': 'answers.not_finite', 'params': {'value': "'inf'"}, 'text': 'x'}},
     "a.csv:3: column 'flywheel.J': invalid answer: not a finite number: 'inf'"),
    ('answers.did_you_mean', {'path': 'flywheel.J'}, "did you mean 'flywheel.J'?"),
    ('answers.no_such_path', {}, 'no such path in the results'),
    ('answers.tol_key_unused', {'key': 'differential.sped', 'hint': 'x'},
     "the tolerance key 'differential.sped' matches no quantity of this task's results (x): "
     "the quantities it was meant for keep the default tolerance"),
    ('answers.note_unknown_path', {'reason': {'code': 'answers.path_no_key', 'params': {'path': 'flywheel.JJ', 'key': 'JJ'},
                                              'text': 'x'},
                                   'hint': {'code': 'answers.did_you_mean', 'params': {'path': 'flywheel.J'}, 'text': 'x'}},
     "flywheel.JJ: no key 'JJ'; did you mean 'flywheel.J'?"),
    ('answers.path_no_key', {'path': 'flywheel.JJ', 'key': 'JJ'}, "flywheel.JJ: no key 'JJ'"),
    ('answers.path_not_list', {'path': 'flywheel.J[2]', 'index': 2}, 'flywheel.J[2]: [2] applied to a non-list'),
    ('answers.path_no_entry', {'path': 'kinematics[99].phi', 'index': 99}, 'kinematics[99].phi: no entry with index 99'),
    ('answers.path_index_range', {'path': 'gears.x[7]', 'index': 7}, 'gears.x[7]: index 7 out of range'),
    ('answers.bad_path', {'path': 'a.'}, "bad path 'a.'"),
    ('input.table_unreadable', {'error': 'Permission denied'}, 'cannot read: Permission denied'),
    ('input.table_not_text', {}, 'not a UTF-8 text table'),
    ('input.table_header_first', {}, 'the header must be the first line'),
    ('input.table_empty', {}, 'empty table (no header line)'),
    ('input.table_malformed_row', {'cells': 4, 'columns': 2}, 'malformed row: 4 cells but the header has 2 columns'),
    ('input.table_cell_long', {'limit': 131072}, 'a cell longer than 131072 characters'),
    ('input.table_rows_many', {'limit': 10000}, 'more than 10000 rows'),
    ('input.table_large', {'size': 20000000, 'limit': 16777216}, 'a table of 20000000 bytes: at most 16777216'),
    ('input.delta_inverse', {'got': 20.0, 'inverse': '1/20'},
     "the coefficient of speed fluctuation is a fraction below 1, got 20: did you mean 1/20?"),
    ('input.tol_not_number', {'what': 'plain', 'got': '-1'},
     'expected a non-negative number (relative tolerance), got -1'),
    ('input.tol_section_not_mapping', {'got': '0.05'},
     "a mapping of a path or prefix (or `default`) to a tolerance, got 0.05: write `tolerance: {default: 0.05}`"),
    ('input.tol_share_large', {'what': 'plain', 'got': '5', 'pct': 500.0, 'share': 0.05},
     "relative tolerance 5 passes every answer within 500 % of the reference: a share is written 0.05 or "
     "'5 %' (did you mean 0.05?)"),
    ('input.tol_unknown_key', {'key': 'rell'},
     "unknown key 'rell'; a tolerance mapping holds `rel`, `abs` and `sign`"),
    ('input.tol_sign', {'got': "'plus'"}, "`sign` of a tolerance is `any` (the magnitude is graded), got 'plus'"),
    ('input.tol_not_file', {}, 'not a regular file (a tolerance file is a YAML mapping)'),
    ('input.tol_not_mapping', {},
     'not a tolerance file (a YAML mapping of result paths or prefixes to tolerances)'),
    ('answers.not_file', {}, 'not a regular file (an answers file is a YAML file with `answers:`)'),
    ('answers.not_mapping', {'got': 'list'}, 'expected a mapping, got a list'),
    ('answers.table_no_variant', {},
     'an answers table needs a `variant` column (and `student`, `group`, then one column per result path)'),
    ('answers.table_row', {'where': 'a.csv:2', 'reason': {'code': 'input.table_malformed_row',
                                                          'params': {'cells': 4, 'columns': 2}, 'text': 'x'}},
     'a.csv:2: malformed row: 4 cells but the header has 2 columns'),
    ('answers.no_source', {}, 'no such file or folder'),
    ('answers.none_in_task', {},
     'no answers to check: add an `answers:` section (paths into results.json) or give --answers FILE'),
    ('quantities.preset_empty', {'preset': 'cam'},
     "preset 'cam': the task's results have none of its quantities (is its section in the task?)"),
    ('quantities.no_position', {'preset': 'kinetostatics[5]', 'index': '5', 'computed': '3, 7'},
     "preset 'kinetostatics[5]': the task's results have no position 5 (positions computed: 3, 7)"),
    ('quantities.preset_meant', {'name': 'kinematic', 'preset': 'kinematics', 'presets': 'positions, kinematics'},
     "quantity 'kinematic' is neither a preset nor a path in the results; did you mean the preset 'kinematics'? "
     "(presets: positions, kinematics)"),
    ('quantities.not_in_results', {'name': 'flywheel.JJ', 'why': "flywheel.JJ: no key 'JJ'",
                                   'hint': {'code': 'answers.did_you_mean', 'params': {'path': 'flywheel.J'}},
                                   'presets': 'positions'},
     "quantity 'flywheel.JJ' is not in the results: flywheel.JJ: no key 'JJ'; did you mean 'flywheel.J'? "
     "(presets: positions)"),
    ('quantities.no_number', {'name': 'flywheel'}, "'flywheel' holds no number"),
    ('sheets.none', {}, "no sheets: the task has nothing the sheets draw (a linkage, a cam, a gear pair, a planetary "
     "gear, a differential, a drive's gear train, balancing)"),
    ('quantities.pattern_empty', {'name': 'gears.q[*]'}, "pattern 'gears.q[*]' matches no quantity of the task's results"),
    ('input.file_not_found', {}, 'file not found'),
    ('input.unknown_keys', {'first': {'code': 'input.unknown_key', 'params': {'key': 'lenght', 'hint': 'length'}},
                            'rest': [{'code': 'input.unknown_also', 'params': {'key': 'masss', 'hint': 'mass'}},
                                     {'code': 'input.unknown_also_plain', 'params': {'key': 'foo'}}]},
     "unknown key 'lenght'; did you mean 'length'? Also unknown: 'masss' (did you mean 'mass'?); 'foo' (no key of "
     "that name here)"),
    ('input.unknown_also', {'key': 'masss', 'hint': 'mass'}, "'masss' (did you mean 'mass'?)"),
    ('input.unknown_also_plain', {'key': 'foo'}, "'foo' (no key of that name here)"),
    ('input.cannot_read', {'reason': 'Permission denied'}, 'cannot read: Permission denied'),
    ('input.not_regular', {'kind': 'folder'}, 'not a regular file (a folder): give a YAML text file'),
    ('input.not_regular', {'kind': 'fifo'}, 'not a regular file (a FIFO (named pipe)): give a YAML text file'),
    ('input.not_regular', {'kind': 'other'}, 'not a regular file (not a regular file): give a YAML text file'),
    ('input.not_regular_now', {}, 'not a regular file: give a YAML text file'),
    ('input.too_large', {'kib': 1024}, 'the file is larger than 1024 KiB: a task (or answers) file is a small text file'),
    ('input.not_text_head', {}, 'not a text file'),
    ('input.not_text', {'encoding': 'UTF-8', 'reason': 'invalid continuation byte', 'byte': 21},
     'not a UTF-8 text file (invalid continuation byte at byte 21); save it as UTF-8'),
    ('answers.bad_path_near', {'path': 'a..b', 'near': '.'}, "bad path 'a..b' near '.'"),
    ('answers.bad_column', {'column': 'a..b', 'reason': {'code': 'answers.bad_path_near',
                                                         'params': {'path': 'a..b', 'near': '.'}, 'text': 'x'}},
     "column 'a..b': bad path 'a..b' near '.'"),
    ('answers.note_not_number', {'kind': 'list', 'hint': {'code': 'answers.no_such_path', 'params': {}, 'text': 'x'}},
     'not a number but a list; no such path in the results'),
    ('answers.not_finite', {'value': 'inf'}, 'not a finite number: inf'),
    ('input.number_not_degree', {'text': '182,14\u00ba', 'sign': '\u00ba', 'code': 'U+00BA'},
     "'182,14\u00ba': '\u00ba' (U+00BA) is not the degree sign: type \u00b0 (U+00B0) or write deg"),
    ('answers.note_no_stage', {'section': 'cam'}, "the task has no 'cam' stage"),
    ('answers.note_no_value', {}, 'no value in the results (singular or not computed)'),
    ('answers.note_missing', {}, 'no value given'),
    ('answers.note_sign', {}, 'right magnitude, wrong sign'),
    ('answers.note_absolute', {}, 'absolute error'),
    ('answers.angle_relative', {'rel': 0.05, 'at90': 4.5, 'paths': ['positions.phi0', 'positions.theta'], 'more': '',
                                'path': 'positions.phi0'},
     "angles were graded with a relative tolerance (0.05): it passes an angle more than 1 deg off (at 90 deg, "
     "4.5 deg either side; a swapped working and idle stroke can pass): positions.phi0, positions.theta. An angle "
     "is better held in degrees: `positions.phi0: {abs: 0.5}` for each, in the task's `tolerance` or in "
     "--tolerance FILE"),
    ('input.flow_open_hint', {'line': 1, 'col': 10}, '; the bracket opened at line 1, column 10 is not closed'),
    ('answers.twice', {'path': 'gears.aw'}, 'gears.aw is answered twice (once with a blank around the path)'),
    ('answers.not_read', {'reason': 'a.yaml: bad'}, 'not read: a.yaml: bad'),
    ('batch.gradebook_unmatched', {'file': 'gradebook-moodle.csv', 'n': 2, 'files': ['a.yaml', 'b.yaml'], 'more': ''},
     "gradebook-moodle.csv: 2 lines have no email and no ID number, by which Moodle's import finds a student "
     "(a.yaml, b.yaml): give `student: {email: ...}` or `id` in the answers"),
    ('batch.flag_same_as', {'who': 'Ivanov'}, 'same answers as Ivanov'),
    ('batch.same_right', {'n': 12}, '12 answers, all within tolerance: right results agree by themselves'),
    ('batch.same_wrong', {'n': 12, 'wrong': 3}, '12 answers, 3 of them outside tolerance: the same mistakes'),
    ('batch.flag_key_of', {'variant': '17'}, "within tolerance of variant 17's key"),
    ('batch.flag_repeat', {'files': ['a.yaml', 'b.yaml']}, 'another submission: a.yaml, b.yaml'),
    ('variants.unused_columns', {'table': 't.csv', 'columns': ['mass'], 'template': 'p.yaml'},
     't.csv: warning: column mass used by no placeholder of p.yaml'),
    ('variants.empty_variant', {}, 'empty `variant` cell'),
    ('variants.empty_cells', {'columns': ['a', 'b']}, 'empty cells in columns a, b'),
    ('variants.not_numbers', {'cells': [{'code': 'variants.column_reason', 'params': {'column': 'n [rpm]',
                                         'reason': {'code': 'input.number_not_number', 'params': {'text': 'x'},
                                                    'text': "'x' is not a number"}}, 'text': ''}]},
     "column n [rpm]: 'x' is not a number"),
    ('variants.column_reason', {'column': 'n', 'reason': 'x'}, 'column n: x'),
    ('variants.row', {'where': 't.csv:3', 'variant': '7', 'reason': 'x'}, 't.csv:3: variant 7: x'),
    ('variants.wrote', {'n': 24, 'total': 25, 'out': 'g', 'csv': 'g/variants.csv'},
     'wrote 24 of 25 variants to g (and g/variants.csv)'),
    ('form.wrote', {'n': 25, 'out': 'forms'}, 'wrote 25 forms and keys to forms'),
    ('answers.not_number_bool', {'value': 'true'}, 'true is a yes/no value, not a number: write the number'),
    ('answers.wrong_unit_latin', {'value': "'13,1 H'", 'written': 'H', 'cyr': '\u041d'},
     "'13,1 H' is not in a unit of this quantity: 'H' in Latin letters is another unit; did you mean '\u041d', in Cyrillic letters?"),
    ('answers.unit_not_course', {'value': "'5 MM'", 'unit': 'MM'},
     "'5 MM' is not in a unit of the course's quantities ('MM' reads as another quantity's unit)"),
    ('answers.wrong_unit', {'value': "'0.67 kg'", 'unit': 'm/s'},
     "'0.67 kg' is not in a unit of this quantity: its unit does not convert to m/s"),
    ('answers.note_unit_slip', {'unit': 'mm', 'si': 'm', 'value': 98.5},
     "a number without a unit is in m; read in mm it is right: write the unit (98.5 mm)"),
    ('input.cam_angles_both', {},
     'give `pressure_angle` or `transmission_angle`, not both'),
    ('input.cam_pressure_range', {},
     'the allowed pressure angle must lie in (0, 90) deg'),
    ('input.cam_rocker_length', {},
     'a rocker follower needs `rocker_length`'),
    ('input.cam_offset_rocker', {},
     '`offset` is for a translating follower'),
    # the chosen cam size and the followers (tmm_cli/cam/chosen.py); the texts as they were written inline
    ('input.cam_roller_flat_knife', {'follower': 'flat'},
     '`roller` is not allowed with a flat-faced follower (it has no roller)'),
    ('input.cam_roller_flat_knife', {'follower': 'knife'},
     '`roller` is not allowed with a knife-edge follower (it has no roller)'),
    ('input.cam_offset_flat', {},
     '`offset` does not change the cam of a flat-faced follower: leave it out'),
    ('input.cam_rho_min_flat', {},
     '`rho_min_allowed` is for a flat-faced follower (`follower: flat`)'),
    ('input.cam_r0_positive', {},
     'the chosen base radius `r0` must be positive'),
    ('input.cam_center_distance_rocker', {},
     '`center_distance` is for a rocker follower with a chosen `r0`'),
    ('input.cam_offset_auto_chosen', {},
     'with a chosen `r0` give the offset (a number, 0 for a central follower), not auto'),
    ('input.cam_r0_below_offset', {'r0': 0.01, 'offset': 0.015},
     'the chosen base radius r0 = 0.01 m is smaller than |offset| = 0.015 m'),
    ('input.cam_rocker_needs_center_distance', {},
     'a rocker with a chosen `r0` needs `center_distance` (cam centre to rocker pivot)'),
    ('input.cam_r0_rocker_range', {'r0': 0.2, 'a': 0.12, 'l': 0.05, 'low': 0.07, 'high': 0.17},
     "no cam centre is 0.2 m from the follower's lowest position and 0.12 m from the pivot of a 0.05 m rocker: "
     "r0 must lie between |center_distance - rocker_length| = 0.07 and 0.17 m"),
    # the crank speed from the output's (tmm_cli/linkage/drive_speed.py)
    ('input.output_no_stroke', {'output': 'ram'},
     "the output 'ram' has no stroke (no extreme positions), so the crank speed cannot follow from its speed: "
     "give drive.speed"),
    ('input.output_rocker_speed', {'output': 'rocker'},
     "the output 'rocker' is a rocker: its speed is an angular speed (rad/s, deg/s)"),
    ('input.output_slider_speed', {'output': 'ram'},
     "the output 'ram' is a slider: its speed is a linear speed (m/s)"),
    ('input.output_no_working_stroke', {},
     'the working stroke is not defined (no extreme positions): give drive.speed'),
    ('input.cam_swing', {},
     'a rocker swing (`stroke`, deg) must be below 180'),
    ('input.ratio_zero', {},
     'the ratio cannot be zero'),
    ('input.planetary_scheme', {'scheme': "'E'", 'known': ['A', 'B', 'C', 'D']},
     "unknown planetary scheme 'E'; known: A, B, C, D"),
    ('input.z_range', {'z_min': 30, 'z_max': 20},
     'z_min = 30 exceeds z_max = 20'),
    ('input.synthesis_and_mechanism', {},
     '`synthesis` generates the mechanism: give either `synthesis` or `mechanism`, not both'),
    ('input.synthesis_drive', {},
     '`synthesis` needs a `drive` section (link: crank, speed, direction)'),
    ('input.detail_needs_mechanism', {},
     '`detail_position` names a position of the linkage: it needs a `mechanism` (or `synthesis`)'),
    ('input.output_speed_bool', {},
     'expected a speed (m/s for a slider, rad/s or deg/s for a rocker), got a boolean'),
    ('input.output_speed_unit', {'value': '3 kg'},
     "'3 kg' is not a speed: give m/s (a slider) or rad/s, deg/s (a rocker)"),
    ('input.output_speed_positive', {'value': "'-0.3 m/s'"},
     "the output speed must be positive, got '-0.3 m/s'"),
    ('input.load_negative_against', {'name': 'magnitude', 'kind': 'resistance', 'value': -12000.0},
     '`magnitude` of a `kind: resistance` load is its size and must not be negative (got -12000); the sense comes from `kind` (against the motion)'),
    ('input.load_negative_along', {'name': 'moment', 'kind': 'driving', 'value': -5.0},
     '`moment` of a `kind: driving` load is its size and must not be negative (got -5); the sense comes from `kind` (along the motion)'),
    # the linkage's references and sizes (the former texts of linkage/mechanism.py, validation.py)
    ('input.ground_is_link', {'name': 'O'},
     "'O' is both a ground point and a link name"),
    ('input.extra_repeats', {'point': 'A'},
     "extra point 'A' repeats a point of the link"),
    ('input.ground_unused', {'point': 'O1'},
     "ground point 'O1' is used by no link"),
    ('input.point_not_ground', {'point': 'O2', 'link': 'rocker', 'ground': 'O3'},
     "point 'O2' of link 'rocker' is on no other link and is no ground point: did you mean the ground point 'O3'?"),
    ('input.drive_slider', {'link': 'ram'},
     "the drive link 'ram' must be a bar (a crank), not a slider"),
    ('input.drive_no_pivot', {'link': 'crank', 'points': "['A', 'B']"},
     "the drive link 'crank' has no ground pivot: one of its points ['A', 'B'] must be listed under mechanism.ground"),
    ('input.slider_self', {},
     'a slider cannot slide on itself'),
    ('input.com_point', {'point': 'Z', 'link': 'rod', 'points': ['A', 'B']},
     "'Z' is not a point of link 'rod' (its points: A, B)"),
    ('input.link_alone', {'link': 'rod'},
     "link 'rod' shares no point with any other link or the ground"),
    ('input.reserved_point', {'point': 'S2', 'index': 2},
     "point name 'S2' is reserved for the centre of mass of link 2"),
    ('input.motion_flywheel', {},
     '`motion: true` needs a `flywheel` section (the steady motion comes from the flywheel)'),
    ('input.load_point', {'point': 'Z', 'link': 'rod', 'points': ['A', 'B']},
     "'Z' is not a point of the mechanism (the points of link 'rod': A, B)"),
    ('input.force_direction', {'link': 'rod'},
     "a force on the bar 'rod' needs `direction` (deg from +x); only a resistance/driving force over a stroke takes the direction of motion"),
    ('input.mm_link', {'link': 'rod'},
     "the length of 'rod'"),
    ('input.mm_ground', {'point': 'O1', 'd': 620.0, 'origin': 'O'},
     'ground point O1 (at 620 m from O)'),
    ('input.mm_suspect', {'what': {'code': 'input.mm_link', 'params': {'link': 'rod'}, 'text': "the length of 'rod'"}, 'value': 350.0, 'ratio': 1000.4, 'lo': 0.08, 'hi': 0.62},
     "the length of 'rod', 350 m, is 1000 times the other lengths (0.08..0.62 m): probably meant in millimetres (write '350 mm')"),
    ('input.mm_suspect_one', {'what': 'the crank', 'value': 80.0, 'ratio': 250.0, 'other': 0.32},
     "the crank, 80 m, is 250 times the other length (0.32 m): probably meant in millimetres (write '80 mm')"),
    ('input.mm_no_assembly', {'suspect': {'code': 'text', 'params': {'text': 'X'}, 'text': 'X'}, 'reason': {'code': 'kinematics.fail.never', 'params': {'group': 'II(2,3)', 'links': ['rod', 'ram']}, 'text': 'x'}},
     'X; the linkage does not assemble: group II(2,3) (links rod, ram) does not assemble at any crank angle'),
    ('input.impossible', {'reason': {'code': 'kinematics.fail.never', 'params': {'group': 'II(2,3)', 'links': ['rod', 'ram']}, 'text': 'x'}, 'links': ['rod', 'ram']},
     'impossible dimensions: group II(2,3) (links rod, ram) does not assemble at any crank angle; check the lengths of rod, ram and the ground points'),
    # the two-degree-of-freedom machine and the gear train: their section checks
    ('input.time_range', {'value': 1e13}, '1e+13 s is out of range'),
    ('input.dof2_negative', {'what': 'mass', 'value': -1.2}, 'mass must not be negative, got -1.2'),
    ('input.rotor_length', {'value': -0.06}, 'the rotor length must be positive, got -0.06'),
    ('input.rotor_inertia_both', {},
     "give the rotor's moment of inertia either about its centre of mass (`J`) or about O (`J_O`), not both"),
    ('input.rotor_J_O', {'J_O': 0.0012, 'm_com2': 0.012},
     'J_O = 0.0012 kg*m^2 is less than m1*com^2 = 0.012: impossible (J_O = J_S1 + m1*com^2 with J_S1 >= 0)'),
    ('input.striker_length', {'value': 0.0}, 'the striker length must be positive, got 0'),
    ('input.striker_mass', {}, 'the striker needs a mass or a moment of inertia (its motion is undetermined)'),
    ('input.dof2_drive_one', {},
     'the drive is either a constant `moment` (N*m) or a held `speed` (omega1 = const), give exactly one'),
    ('input.dof2_speed_positive', {'value': -157.08},
     'the drive speed must be positive (use `direction`), got -157.08'),
    ('input.dof2_direction_moment', {}, '`direction` belongs to a `speed` drive; a moment is signed (ccw positive)'),
    ('input.dof2_duration', {}, 'give the duration either as `t_end` (s) or as `turns` (of the rotor), exactly one'),
    ('input.dof2_positive', {'name': 't_end', 'value': -0.04}, 't_end must be positive, got -0.04'),
    ('input.dof2_samples', {'value': 1}, 'samples must be between 2 and 100001, got 1'),
    ('input.dof2_omega', {'omega1': 157.07963267948966, 'omega': 3.0},
     'with a `speed` drive the rotor turns at omega1 = 157.08 rad/s; initial.omega = 3 contradicts it (omit it)'),
    ('input.train_needs_scheme', {}, 'a planetary stage needs `scheme: A | B | C | D`'),
    ('input.train_scheme_pair', {}, '`scheme` belongs to planetary stages, not to a pair'),
    ('input.train_internal', {}, '`internal` belongs to pairs, not to a planetary stage'),
    ('input.train_z_count_pair', {'n': 2, 'got': 3}, 'a pair takes 2 tooth numbers, got 3'),
    ('input.train_z_count_scheme', {'scheme': 'A', 'n': 3, 'got': 2}, 'scheme A takes 3 tooth numbers, got 2'),
    ('input.train_z_and_ratio', {}, "give either `z` or the stage's `ratio`, not both"),
    ('input.train_z_above_max', {'name': 'z_min_internal', 'value': 85, 'z_max': 20},
     'z_min_internal = 85 exceeds z_max = 20'),
    ('input.train_z_300', {}, 'tooth numbers above 300 are not supported'),
    ('input.diff_member', {'key': '4', 'scheme': 'A', 'members': ['1', '3', 'H']},
     "'4' is not a member of scheme A: the members are 1, 3, H"),
    ('input.diff_two_speeds', {'got': 1, 'members': ['1', '3', 'H']},
     "give the speeds of exactly two members of 1, 3, H (got 1)"),
    ('input.diff_one_torque', {'got': 2}, 'give the torque of one member at most (got 2)'),
    ('input.diff_member_twice', {'member': 'H', 'keys': ['h', 'H']}, 'member H is given twice (as h, H)'),
    ('input.synthesis_drive_crank', {'link': 'rocker'}, "a synthesis designs the linkage with its crank driving: "
     "`drive.link` must be `crank` (got 'rocker')"),
    ('input.synth_function', {'reason': "unknown name 'z'"}, "the function to generate: unknown name 'z'"),
    ('input.synth_range_zero', {}, 'the range of the angle must not be zero'),
    ('input.synth_x_range', {}, 'the range of x must have two different ends'),
    ('input.synth_function_not_finite', {'x': 2.0, 'x0': 1.0, 'x1': 4.0},
     'y(x) is not a finite number at x = 2 (the range of x is 1 to 4): change `function` or `x`'),
    ('input.synth_function_ends', {'y': 0.0, 'x0': 0.0, 'x1': 3.141592653589793},
     "y(x) takes the same value 0 at both ends of the range of x (0 and 3.14159): the rocker's angle, linear in y "
     'between them, is undefined; change `function` or `x`'),
    ('synthesis.fail.function_range', {}, 'synthesis: the function is not finite over the range of x, or '
     'y(x0) = y(x1): change `function` or `x`'),
    ('synthesis.fail.function_points', {}, 'synthesis: the precision points give no Freudenstein solution '
     '(singular equations): change the ranges of `input` or `output`'),
    ('synthesis.fail.function_lengths', {'what': 'crank', 'K': 'K1', 'Kv': -3.0, 'a': -0.1, 'c': 0.2, 'b2': 0.01},
     "synthesis: Freudenstein's solution has no four-bar: K1 = -3 gives no positive crank length (crank = "
     '`frame`/K1 = -0.1 m, rocker = `frame`/K2 = 0.2 m, coupler squared = a^2 + c^2 + d^2 - 2 a c K3 = 0.01 m^2; '
     'each must be positive): change `frame` or the ranges of `input` and `output`'),
    ('synthesis.fail.function_turn', {'what': 'rocker', 'a': 0.0671104, 'c': -0.0931983, 'crank': 0.0671104,
                                      'coupler': 0.191634, 'rocker': 0.0931983, 'fix': ['`output.start: 280`']},
     "synthesis: Freudenstein's solution gives a negative rocker length (crank = `frame`/K1 = 0.0671104 m, "
     'rocker = `frame`/K2 = -0.0931983 m): a negative length is the link pointing the other way, so this is the '
     "four-bar with crank 0.0671104 m, coupler 0.191634 m and rocker 0.0931983 m, the rocker's angles measured "
     'from the opposite direction (turned by 180 deg); the angles stay as the task gives them: write '
     '`output.start: 280` (the start plus 180 deg) and run again'),
    ('synthesis.fail.function_branch', {'x': 1.25}, "synthesis: the precision points lie on the two different "
     "assemblies of Freudenstein's four-bar (x = 1.25 needs the other one: a branch defect), so no one linkage "
     'passes them all: change the ranges of `input` or `output`, or their starts'),
    ('synthesis.fail.function_assembly', {'phi': 128.5, 'x': 1.7, 'start': 45.0, 'end': 165.0},
     'synthesis: the generated four-bar does not assemble at the crank angle 128.5000 deg (x = 1.7) of the input '
     'range 45..165 deg: narrow `input.range` (or `output.range`), move `input.start` or `output.start`, or '
     'change `frame`'),
    ('positions.zero_range', {'start': 45.0},
     "positions: `positions.zero` is not used: over the input range position 0 is the range's start (45 deg)"),
    ('positions.input_range', {'kind': 'double-rocker', 'count': 12, 'start': 45.0, 'end': 105.0},
     "positions: the generated four-bar is a double-rocker, not a crank-rocker: the 12 positions are spread over "
     "the input range 45..105 deg, both ends included; the extreme positions, the coefficient K and the flywheel "
     "need a crank-rocker's full cycle and are not found"),
    ('positions.fail.range_no_stroke', {'link': 'rocker'},
     "the crank works over the input range only, so the output link 'rocker' has no extreme positions and "
     "stroke-based loads cannot be placed"),
    ('flywheel.skipped_range', {'start': 45.0, 'end': 105.0},
     "flywheel: not computed: the crank works over the input range only (45..105 deg), and the flywheel needs "
     "the machine's full cycle"),
    ('balancing.apply_unused', {}, "balancing: `apply: true` changes nothing here: the counterweights act on the "
     'kinetostatics and the flywheel, and the task asks for neither'),
    ('balancing.skipped_range', {'start': 45.0, 'end': 105.0},
     'balancing: not computed: the crank works over the input range only (45..105 deg), and balancing the '
     'linkage needs its full turn'),
    ('input.synth_collinear', {'name': 'A', 'points': '(0, 0), (0.1, 0), (0.2, 0)'},
     'the three positions of the moving pivot A lie on one line (0, 0), (0.1, 0), (0.2, 0): no circle passes '
     'through them; move the pivot or change `positions`'),
    ('input.synth_pivots_same', {}, 'the moving pivots A and B coincide: the coupler needs two pivots apart'),
    ('input.synth_positions_same', {'i': 1, 'j': 2}, 'positions 1 and 2 of the plane are the same: the pole method '
     'needs three different positions'),
    ('input.synth_points_same', {}, 'the points of the path all coincide: give points that trace a path'),
    ('input.synth_points_function', {}, 'function generation takes `points` as the number of precision points '
     '(3 to 5)'),
    ('input.synth_points_path', {}, 'path generation takes `points` as a list of 5 to 20 points [x, y]'),
    ('synthesis.fail.positions_crank', {'a': 0.25, 'b': 0.3, 'c': 0.22, 'd': 0.3},
     "synthesis: the linkage through the three positions has the crank 0.25 m, coupler 0.3 m, rocker 0.22 m and "
     "frame 0.3 m: by Grashof's rule its crank cannot turn fully; move `moving_pivots` or change `positions`"),
    ('synthesis.fail.path_none', {'gamma': 30.0}, 'synthesis: no crank-rocker with the least transmission angle '
     '30 deg was found whose coupler point passes near the points: lower `gamma_min` or change `points`'),
    # the synthesis' former f-strings (each text below is their output for these params)
    ('synthesis.fail.quick_return', {'what': 'offset_slider_crank', 'K': 1.0, 'theta': 0.0},
     'synthesis.K: an offset slider-crank needs K > 1 (theta > 0); got K = 1 (theta = 0 deg): raise K (K = 1: use type slider_crank)'),
    ('synthesis.fail.quick_return', {'what': 'slotted_lever', 'K': 0.8947368421052632, 'theta': -10.0},
     'synthesis.K: a slotted-lever mechanism needs K > 1 (theta > 0); got K = 0.894737 (theta = -10 deg): raise K (K = 1: use type slider_crank)'),
    ('synthesis.fail.theta_180', {'theta': 180.0},
     'synthesis.theta: theta = 180 deg must be below 180 deg: lower K or theta'),
    ('synthesis.fail.offset_large', {'e': 0.8, 'e_max': 0.6955152771773473},
     'synthesis.e: the offset e = 0.8 m is too large for H and K: it must be below H/(2 tan(theta/2)) = 0.695515 m; lower e or K'),
    ('synthesis.fail.offset_K', {'K': 3.5},
     'synthesis.K: no offset slider-crank reaches K = 3.5 with stroke H: lower K'),
    ('synthesis.fail.offset_gamma', {'gamma': 60.0, 'K': 1.2, 'g_max': 47.123456789, 'e': 0.0512345678},
     'synthesis.gamma_min: gamma_min = 60 deg is too large for K = 1.2: an offset slider-crank reaches at most 47.1235 deg (offset 0.0512346 m); lower gamma_min or K'),
    ('synthesis.fail.offset_reach_e', {'e': 0.3, 'e_max': 0.1234567891},
     'synthesis.e: with these H, K and e = 0.3 m the folded extreme position falls behind the foot of the perpendicular from the crank axis to the guide (4 l_OA l_AB < H^2), so no slider-crank has them: lower e (at most 0.123457 m) or K'),
    ('synthesis.fail.offset_reach_lambda', {'lam': 5.0, 'lam_max': 6.78901234},
     'synthesis.lambda: with these H, K and lambda = 5 the folded extreme position falls behind the foot of the perpendicular from the crank axis to the guide (4 l_OA l_AB < H^2), so no slider-crank has them: lower lambda (at most cot^2(theta/2) = 6.78901) or K'),
    ('synthesis.fail.crank_rocker_none', {'psi': 40.0, 'K': 1.2, 'rocker': 0.3, 'frame': 5.0},
     "synthesis: no crank-rocker has psi = 40 deg, K = 1.2, rocker 0.3 m and frame 5 m (the crank pivot circle at `frame` from O1 misses the circle seeing the rocker's chord under theta, or the crank cannot turn): change frame or rocker, or lower psi or K"),
    ('synthesis.fail.guide_height', {'theta': 26.666666666666668, 'h': 0.3, 'stroke': 0.14220261226289763, 'H': 0.4, 'h_need': 0.8456789},
     'synthesis.guide_height: with the swing psi = theta = 26.6667 deg a ram guide at 0.3 m above O1 gives the stroke 2 guide_height tan(psi/2) = 0.142203 m, not H = 0.4 m: omit guide_height (then 0.845679 m) or change H'),
    ('synthesis.fail.slotted_guide', {'L': 0.2, 'need': 0.30831055079837605},
     'synthesis.rocker: the slotted link (0.2 m) does not reach the ram guide at its extreme positions (needs guide_height/cos(psi/2) = 0.308311 m): lengthen it'),
    ('synthesis.fail.slotted_short', {'L': 0.2, 'reach': 0.3690983},
     'synthesis.rocker: the slotted link (0.2 m) is shorter than frame + crank = 0.369098 m, the farthest reach of the block: lengthen it or shorten frame'),
    ('synthesis.fail.slotted_short_shaper', {'L': 0.2, 'reach': 0.3690983},
     'synthesis.rocker: the slotted link (0.2 m) is shorter than frame + crank = 0.369098 m, the farthest reach of the block: lengthen it (raise H) or shorten frame'),
    # new texts
    ('input.synth_K_below_one', {'type': 'crank_rocker', 'key': 'K', 'value': 0.8},
     "type crank_rocker needs K >= 1 (theta >= 0 deg): K = (180 + theta)/(180 - theta) is the ratio of the crank's "
     "turns over the slow and the quick strokes; got `K` = 0.8"),
    ('input.synth_quick_return', {'type': 'shaper', 'key': 'theta', 'value': -10.0},
     "type shaper needs K > 1 (theta > 0 deg): its working stroke is the slow one, K = (180 + theta)/(180 - theta); "
     "got `theta` = -10 (K = 1: use type slider_crank)"),
    ('synthesis.path_far', {'dev': 0.3812345, 'point': 7, 'share': 0.19061725, 'extent': 2.0, 'limit': 0.05},
     "synthesis: the coupler curve passes far from the points: point 7 is 0.381 m from it, 19.1% of the points' "
     "extent 2 m (more than 5%); no crank-rocker keeping the constraints was found nearer: check `max_deviation`, "
     "give points nearer a coupler curve, or lower `gamma_min`"),
    ('input.balancing_radius', {'method': 'full', 'key': 'rocker'},
     'counterweights by the full method need `radius: {rocker: ...}` (m)'),
    ('input.balancing_radius_positive', {'key': 'crank'}, "the counterweight's radius `crank` must be above zero"),
    ('input.balancing_share_full', {}, "`reciprocating_share` belongs to the `crank` method (a slider-crank): the "
     "`full` method balances a four-bar's shaking force completely"),
    ('input.balancing_rocker_crank', {}, "the `crank` method is a slider-crank's (a counterweight on the crank only), "
     "yet a rocker's radius is given: a four-bar (a crank and a rocker) takes `method: full`"),
    ('input.balancing_apply_needs', {}, "`apply: true` needs `counterweights`: there is nothing to apply"),
    ('input.rotor_planes_equal', {}, 'the two correction planes must be at different z'),
    ('input.balancing_needs_mechanism', {}, 'counterweights balance a linkage: the task needs a `mechanism`'),
    ('input.balancing_nothing', {}, '`balancing` without a linkage balances a `rotor`: give `rotor` (or the '
     '`mechanism` whose shaking force it computes)'),
    ('balancing.method_needs', {'method': 'full', 'kind': 'four-bar linkage'},
     'counterweights by the full method need a four-bar linkage: the crank, the coupler and the rocker (full) '
     'or the crank, the connecting rod and a slider on a fixed guide (crank)'),
    ('drive_train.given_tooth_limits', {'stage': 0, 'scheme': 'A', 'z': [32, 20, 72],
                                        'violations': ['z3 = 72 < 85 (internal wheel)']},
     'drive_train: stage 0 (planetary A, z = 32, 20, 72): the given teeth break the tooth limits of zero-shift '
     'wheels (z3 = 72 < 85 (internal wheel)); computed as given'),
    ('drive_train.given_assembly', {'stage': 0, 'scheme': 'A', 'z': [18, 34, 86], 'k': 3, 'fits': [1, 2, 4]},
     'drive_train: stage 0 (planetary A, z = 18, 34, 86): 3 equally spaced satellites cannot be assembled '
     '(computed as given); numbers of satellites that assemble and fit: 1, 2, 4'),
    ('differential.not_coaxial', {'a1': 45.0, 'a2': 46.0},
     'the wheels are not coaxial: the meshes\' centre distances are 45 and 46 (in modules x 2, i.e. tooth sums)'),
    ('differential.adjacency', {'k': 9, 'margin': -3.25},
     '9 satellites do not fit side by side (margin -3.25 modules): use fewer satellites'),
    ('differential.rigid', {'last': '4'}, 'with u = 1 the wheels 1 and 4 always turn together: their speeds do '
     "not give the carrier's; give the speed of H and one wheel"),
    ('differential.tooth_limits', {'violations': ['z3 = 72 < 85 (internal wheel)']},
     'differential: the given teeth break the tooth limits of zero-shift wheels (z3 = 72 < 85 (internal wheel)); '
     'computed as given'),
    ('differential.assembly', {'k': 3, 'fits': [1, 2, 4]}, 'differential: 3 equally spaced satellites cannot be '
     'assembled with these teeth (computed as given); numbers of satellites that assemble and fit: 1, 2, 4'),
    ('differential.fail.self_locking', {'u': 1.05, 'eta': 0.9}, 'the train self-locks for this torque: with '
     'u = 1.05 and efficiency 0.9 no direction of the power flow balances the torques'),
    ('differential.fail.indeterminate', {'u': 1.1025641025641026, 'eta': 0.9, 'value': 40.0, 'last': '4',
                                         't1_first': -5200.0, 't1_last': 177.72151898734177},
     "the carrier's torque TH = 40 N*m does not determine the others: with u = 1.10256 and efficiency 0.9 both "
     'directions of the power flow in the motion relative to the carrier balance it: T1 = -5200 N*m when wheel 1 '
     'drives that motion, T1 = 177.722 N*m when wheel 4 drives it (which one holds is set by the drive, not by '
     'this torque); give the torque of wheel 1 or 4 instead'),
    ('differential.carrier_unbalanced', {'value': 5.0, 'last': '4'},
     'with u = 1 and no loss in the motion relative to the carrier (efficiency 1, or wheel 1 turning with the '
     'carrier) wheel 4 takes T4 = -T1 whatever T1, so T1 + T4 + TH = 0 holds only with TH = 0: the carrier\'s '
     'torque 5 N*m cannot be balanced; give the torque of wheel 1 or 4'),
    ('differential.carrier_indeterminate', {'u': 1.0, 'eta': 1.0, 'last': '4'},
     "the carrier's torque TH = 0 leaves the torques undetermined: with u = 1 and efficiency 1 wheel 4 takes "
     'T4 = -u eta^k T1 = -T1 whatever T1 and the carrier nothing; give the torque of wheel 1 or 4'),
    ('input.synth_needs', {'type': 'slider_crank', 'key': 'H'}, 'type slider_crank needs `H`'),
    ('input.synth_not_taken', {'type': 'crank_rocker', 'key': 'H'}, 'type crank_rocker does not take `H`'),
    ('input.synth_not_taken_offset', {'type': 'slider_crank', 'key': 'e'},
     'type slider_crank does not take `e`; use type offset_slider_crank'),
    ('input.synth_one_of', {'type': 'crank_rocker', 'names': ['`K`', '`theta`']},
     'type crank_rocker needs exactly one of `K`, `theta`'),
    ('input.synth_one_of_got', {'type': 'offset_slider_crank', 'names': ['`e`', '`lambda`', '`gamma_min`'],
                                'given': ['e', 'gamma_min']},
     'type offset_slider_crank needs exactly one of `e`, `lambda`, `gamma_min`; got e, gamma_min'),
    ('input.synth_central', {},
     'a central slider_crank has K = 1 (theta = 0): for K != 1 use type offset_slider_crank'),
    ('input.synth_no_link', {'type': 'slider_crank', 'name': 'zzzzz', 'links': ['crank', 'rod', 'slider']},
     "type slider_crank generates no link 'zzzzz' (links: crank, rod, slider)"),
    ('input.synth_no_link_hint', {'type': 'slider_crank', 'name': 'rood', 'hint': 'rod',
                                  'links': ['crank', 'rod', 'slider']},
     "type slider_crank generates no link 'rood'; did you mean 'rod'? (links: crank, rod, slider)"),
    # an invalid task (TaskError): the lines of `tmm run` on a broken task (stderr as before)
    ('input.issues', {'issues': [
        {'code': 'input.at_field', 'params': {'where': 't.yaml:12:29', 'field': 'mechanism.links.crank.lenght',
                                              'message': {'code': 'input.unknown_key', 'params': {
                                                  'key': 'lenght', 'hint': 'length'}, 'text': 'x'}}, 'text': 'x'},
        {'code': 'input.at', 'params': {'where': 't.yaml:19:1', 'message': {
            'code': 'input.tab', 'params': {}, 'text': 'x'}}, 'text': 'x'}]},
     "t.yaml:12:29: field 'mechanism.links.crank.lenght': unknown key 'lenght'; did you mean 'length'?\n"
     "t.yaml:19:1: use spaces for indentation: this line is indented with a tab, which YAML does not allow"),
    ('input.at', {'where': 't.yaml:1:1', 'message': {'code': 'input.not_mapping', 'params': {}, 'text': 'x'}},
     't.yaml:1:1: the task file must be a mapping of sections (schema: tmm/1, ...)'),
    ('input.at_field', {'where': 't.yaml:16:1', 'field': 'drive.link',
                        'message': {'code': 'input.missing', 'params': {}, 'text': 'x'}},
     "t.yaml:16:1: field 'drive.link': required field is missing"),
    ('input.missing', {}, 'required field is missing'),
    ('input.literal', {'expected': ["'working'", "'idle'", "'both'"], 'got': "'work'"},
     "Input should be 'working', 'idle' or 'both'; got 'work'"),
    ('input.literal_hint', {'expected': ["'sine'", "'cosine'"], 'got': "'linear'", 'hint': "'cosine'"},
     "Input should be 'sine' or 'cosine'; got 'linear'; did you mean 'cosine'?"),
    ('input.int_parsing', {}, 'Input should be a valid integer, unable to parse string as an integer'),
    ('input.float_parsing', {}, 'Input should be a valid number, unable to parse string as a number'),
    ('input.bool_parsing', {}, 'Input should be a valid boolean, unable to interpret input'),
    ('input.int_from_float', {}, 'Input should be a valid integer, got a number with a fractional part'),
    ('input.int_type', {}, 'Input should be a valid integer'),
    ('input.float_type', {}, 'Input should be a valid number'),
    ('input.bool_type', {}, 'Input should be a valid boolean'),
    ('input.string_type', {}, 'Input should be a valid string'),
    ('input.dict_type', {}, 'Input should be a valid dictionary'),
    ('input.list_type', {}, 'Input should be a valid list'),
    ('input.tuple_type', {}, 'Input should be a valid tuple'),
    ('input.finite_number', {}, 'Input should be a finite number'),
    ('input.model_type', {'class_name': 'LinkSpec'}, 'Input should be a valid dictionary or instance of LinkSpec'),
    ('input.greater_than', {'gt': '0'}, 'Input should be greater than 0'),
    ('input.greater_than_equal', {'ge': '2'}, 'Input should be greater than or equal to 2'),
    ('input.less_than', {'lt': '1.5'}, 'Input should be less than 1.5'),
    ('input.less_than_equal', {'le': '3600'}, 'Input should be less than or equal to 3600'),
    ('input.too_short', {'field_type': 'List', 'min_length': '2', 'actual_length': '1'},
     'List should have at least 2 items after validation, not 1'),
    ('input.too_long', {'field_type': 'Tuple', 'max_length': '2', 'actual_length': '3'},
     'Tuple should have at most 2 items after validation, not 3'),
    ('input.not_mapping', {}, 'the task file must be a mapping of sections (schema: tmm/1, ...)'),
    ('input.schema', {'got': "'tmm/2'"}, "unsupported schema 'tmm/2'; this tool reads 'tmm/1'"),
    ('input.text_control', {'char': 'U+0001'},
     'the character U+0001 (a control character or not a character) is not allowed in a text'),
    ('input.text_long', {'n': 1200, 'limit': 1000}, 'a text of 1200 characters: at most 1000 are allowed'),
    ('input.text_combining', {'limit': 30}, 'more than 30 combining marks in a row'),
    ('input.positions_many', {'n': 3700, 'count': 3600, 'extra': 100, 'limit': 3600},
     '3700 positions (count 3600 + 100 extra): at most 3600'),
    ('input.extra_points_many', {'n': 600, 'limit': 500}, '600 extra points on the links: at most 500'),
    ('input.extra_positions_many', {'n': 101, 'limit': 100},
     '101 extra positions: at most 100 (each is drawn on its own; for a finer grid raise `count`)'),
    ('input.forces_many', {'n': 300, 'limit': 200}, '300 forces: at most 200'),
    ('input.ks_positions_empty', {},
     'an empty list computes nothing: list the position numbers or write `all`'),
    ('input.unknown_key', {'key': 'lenght', 'hint': 'length'}, "unknown key 'lenght'; did you mean 'length'?"),
    ('input.unknown_key_allowed', {'key': 'zzz', 'allowed': ['s', 'value']}, "unknown key 'zzz'; allowed: s, value"),
    ('input.key_not_name', {'key': 'True', 'allowed': ['on', 'kind']},
     "unknown key 'True' (keys are names; allowed: on, kind)"),
    ('input.length_positive', {}, '`length` must be positive'),
    ('input.diagram_lengths', {'n_x': 4, 'n_value': 3}, 'abscissa and `value` differ in length (4 vs 3)'),
    ('input.no_link', {'name': 'krank', 'hint': 'crank'}, "no link named 'krank'; did you mean 'crank'?"),
    ('input.no_link_list', {'name': 'zz', 'links': ['crank', 'rod']}, "no link named 'zz'; links: crank, rod"),
    ('input.assembly_point', {'point': 'Q'}, "assembly hint for unknown point 'Q'"),
    ('input.guide_through', {'point': 'Z'},
     "'Z' is not a ground point (fixed guides pass through ground points or [x, y])"),
    ('input.unit_unknown', {'text': '90 rmp', 'unit': 'rmp', 'kind': 'speed'},
     "unknown unit in '90 rmp' ('rmp' is not defined in the unit registry); expected an angular speed (rad/s, rpm)"),
    ('input.unit_no_number', {'text': 'mm', 'kind': 'length'},
     "'mm' is a unit without a number; expected a length (m, mm, cm...) written as a number and its unit"),
    ('input.unit_not_convert', {'text': '0.35 kg', 'kind': 'length', 'unit': 'm'},
     "'0.35 kg' is not a length (m, mm, cm...): its unit does not convert to m"),
    ('input.unit_not_kind', {'text': '3 m', 'kind': 'force_or_pressure'},
     "'3 m' is not a force (N) or, with `area`, a pressure (Pa)"),
    ('input.unit_expected', {'kind': 'length', 'got': 'NoneType'}, 'expected a length (m, mm, cm...), got nothing'),
    ('input.number_not_number', {'text': 'abc'}, "'abc' is not a number"),
    ('input.number_dms', {'text': '36°60′'}, "'36°60′': minutes and seconds of an angle are below 60 (36°8′, 36°08′30″)"),
    ('input.number_prefix', {'text': '≈0,59', 'prefix': '≈'},
     "'≈0,59' is not a number: it begins with '≈'; write the number alone, its unit after it"),
    ('input.number_plus_minus', {'text': '0,59 ± 0,02'},
     "'0,59 ± 0,02' is not one number: write the value alone, without its error after ±"),
    ('input.number_marks', {'text': '1,2,3'}, "'1,2,3' is not a number: it has more than one decimal mark"),
    ('input.number_groups', {'text': '1 23,4'},
     "'1 23,4' is not a number: digits are grouped by spaces in threes only (1 234 567,8)"),
    ('input.number_expression', {'text': '9**9**9'},
     "'9**9**9' is not a number but an expression; numbers are read as written and never computed"),
    ('input.number_dash', {'text': '–5'}, "'–5': a dash is not a minus sign; write '-' or '−'"),
    ('input.number_unit_syntax', {'text': '216 kg m2', 'unit': 'kg m2'},
     "'216 kg m2': cannot read the unit 'kg m2'; units are written as mm, N*m, kg*m^2, m/s^2, rad/s, 1/min "
     "(a power of one digit)"),
    ('input.number_unit_unknown', {'text': '5 parrots', 'unit': 'parrots'}, "'5 parrots': 'parrots' is not a unit tmm knows"),
    ('input.number_frequency', {'text': '120 kHz'},
     "'120 kHz' is a frequency, not an angular speed: write rpm (min^-1) or rad/s (s^-1)"),
    ('input.reading_per_min', {'field': 'drive.speed', 'text': '120 min^-1', 'rpm': 120, 'omega': 12.566370614359172},
     "drive.speed: '120 min^-1' is read as 120 rpm = 12.5664 rad/s: a speed in min^-1 counts revolutions per "
     "minute (the course's n = 120 min^-1)"),
    ('input.reading_hz', {'field': ['drive.speed', 'planetary.speed'], 'text': '2 Hz', 'rps': 2,
                          'omega': 12.566370614359172},
     "drive.speed, planetary.speed: '2 Hz' is read as 2 revolutions per second = 12.5664 rad/s"),
    ('input.reading_per_s', {'field': 'drive.speed', 'text': '12,57 s^-1', 'omega': 12.57},
     "drive.speed: '12,57 s^-1' is read as 12.57 rad/s: an angular velocity in s^-1 is in radians per second "
     "(the course's ω = 12,57 s^-1)"),
    ('input.reading_grad', {'field': 'cam.phases.rise', 'text': '90 grad', 'deg': 90},
     "cam.phases.rise: '90 grad' is read as 90°: grad is degrees, as course books write it; gradians are written "
     "`gon`"),
    ('input.number_bool', {}, 'expected a number, got a boolean'),
    ('input.not_finite', {}, 'expected a finite number'),
    ('input.out_of_range', {'value': 2e12, 'limit': 1e12},
     "2e+12 is out of range: |value| must not exceed 1e+12 (in the field's base unit)"),
    ('input.fraction_zero', {}, 'division by zero in a fraction'),
    ('input.yaml_syntax', {'problem': "mapping values are not allowed here",
                           'hint': {'code': 'input.indent_hint', 'params': {'prev': 23, 'line': 24, 'col_prev': 3,
                                                                            'col_line': 4}, 'text': 'x'}},
     "YAML syntax error: mapping values are not allowed here; check the indentation of lines 23 and 24: the keys "
     "of one section start in the same column (line 23 starts in column 3, line 24 in column 4)"),
    ('input.indent_hint', {'prev': 10, 'line': 11, 'col_prev': 5, 'col_line': 3},
     "; check the indentation of lines 10 and 11: the keys of one section start in the same column (line 10 "
     "starts in column 5, line 11 in column 3)"),
    ('input.yaml_colon', {}, 'mapping values are not allowed here'),
    ('input.yaml_end', {}, 'found unexpected end of stream'),
    ('input.yaml_no_colon', {}, "could not find expected ':'"),
    ('input.yaml_no_key', {}, 'did not find expected key'),
    ('input.yaml_block_end', {'found': '<block mapping start>'}, "expected <block end>, but found '<block mapping start>'"),
    ('input.yaml_flow', {'close': ']', 'got': '<stream end>'}, "expected ',' or ']', but got '<stream end>'"),
    ('input.yaml_char', {'char': '@'}, "found character '@' that cannot start any token"),
    ('input.tab', {}, 'use spaces for indentation: this line is indented with a tab, which YAML does not allow'),
    ('input.duplicate_key', {'key': 'output', 'first': 20}, "duplicate key 'output' (first given on line 20)"),
    ('input.decimal_comma', {'fixed': '0.35', 'given': '0,35'},
     "use a decimal point: 0.35, or quote the value: '0,35' (YAML reads 0,35 inside [...] or {...} as two numbers or "
     "as text)"),
    ('input.decimal_comma_value', {'fixed': '2.1', 'given': '2,1'},
     "'2,1' has a decimal comma, and YAML splits a number at the comma inside [...] or {...}: write 2.1, "
     "or quote the value"),
    ('input.yaml_comma', {}, 'a stray comma: delete it (a comma separates the items inside [...] or {...}; '
     'a line of a section ends without one)'),
    ('input.ks_positions_list', {'got': '2'}, 'a list of positions, e.g. [2] (or all); got 2'),
    ('input.schema_missing', {}, 'add `schema: tmm/1` as the first line'),
    # the failures of a stage (StageError): the former f-strings of the stages
    ('cam.fail.pressure_range', {'phase': 'rise', 'value': 95.0},
     'allowed pressure angle on the rise must lie in (0, 90) deg, got 95'),
    ('cam.fail.no_region', {},
     'no cam centre satisfies the allowed pressure angles (the admissible region is empty); increase the allowed pressure angle, the phase angles or the rocker length, or reduce the swing'),
    ('cam.fail.rocker_hint', {'swing': 30.0, 'half': 15.0},
     ' (a rocker swinging 30 deg usually needs allowed pressure angles above half the swing, 15 deg)'),
    ('cam.fail.with_hint', {'first': {'code': 'cam.fail.no_region', 'params': {}, 'text': 'no cam centre satisfies the allowed pressure angles (the admissible region is empty); increase the allowed pressure angle, the phase angles or the rocker length, or reduce the swing'}, 'hint': {'code': 'cam.fail.rocker_hint', 'params': {'swing': 30.0, 'half': 15.0}, 'text': ' (a rocker swinging 30 deg usually needs allowed pressure angles above half the swing, 15 deg)'}},
     'no cam centre satisfies the allowed pressure angles (the admissible region is empty); increase the allowed pressure angle, the phase angles or the rocker length, or reduce the swing (a rocker swinging 30 deg usually needs allowed pressure angles above half the swing, 15 deg)'),
    ('cam.fail.no_region_either', {'hint': {'code': 'cam.fail.rocker_hint', 'params': {'swing': 30.0, 'half': 15.0}, 'text': ' (a rocker swinging 30 deg usually needs allowed pressure angles above half the swing, 15 deg)'}},
     'no cam centre satisfies the allowed pressure angles for either swing sense (the admissible region is empty); increase the allowed pressure angle, the phase angles or the rocker length, or reduce the swing (a rocker swinging 30 deg usually needs allowed pressure angles above half the swing, 15 deg)'),
    ('cam.fail.unknown_follower', {'follower': 'hammer'},
     "unknown follower 'hammer'"),
    ('cam.fail.stroke', {},
     'the stroke must be positive'),
    ('cam.fail.unknown_law', {'law': 'parabolic'},
     "unknown motion law 'parabolic'"),
    ('cam.fail.rocker_length', {},
     'a rocker follower needs a positive rocker_length'),
    ('cam.fail.phases_positive', {},
     'the rise and return phases must be positive'),
    ('cam.fail.phases_sum', {'total': 350.5},
     'the phases sum to 350.5 deg, not 360'),
    ('cam.fail.zero_r0', {},
     'degenerate cam: zero base radius'),
    ('cam.fail.pressure_exceeded', {'phase': 'dwells', 'limit': 30.0, 'got': 30.0123456789},
     'no cam centre found that keeps the pressure angle on the dwells within 30 deg (best found: 30.0123 deg); increase the allowed pressure angle, the phase angles or the rocker length, or reduce the swing'),
    ('cam.fail.cusp', {},
     'the pitch profile has a cusp (its tangent vanishes)'),
    ('cam.fail.roller_positive', {},
     'the roller radius must be positive'),
    ('cam.fail.roller_undercut', {'roller': 12.0, 'rho': 10.1234, 'phi': 77.777},
     'the roller (r = 12.000 mm) undercuts the profile: minimum radius of curvature of the pitch profile 10.123 mm at phi = 77.78 deg'),
    ('cam.fail.roller_r0', {'roller': 12.0, 'r0': 40.0},
     'the roller (r = 12.000 mm) is not smaller than the base radius r0 = 40.000 mm'),
    ('cam.fail.flat_corner', {'phis': [0.0, 120.0, 123.456789]},
     'a flat-faced follower needs a motion law without velocity jumps: the profile would have a corner at phi = 0, 120, 123.5 deg; choose another law (cosine, sine, poly345, ...)'),
    ('cam.fail.flat_r0', {'r0': 20.0, 'rho': 7.655, 'phi': 181.2345, 'allowed': 10.0, 'r0_min': 22.345},
     'the chosen base radius r0 = 20.000 mm gives the profile a least radius of curvature r0 + s + d2s/dphi2 = 7.655 mm at phi = 181.23 deg, below the allowed 10.000 mm; the least r0 is 22.345 mm'),
    ('cam.fail.zero_r0_flat', {},
     'degenerate cam: zero base radius (give `rho_min_allowed`)'),
    ('cam.fail.chosen_pressure', {'r0': 30.0, 'theta': 33.456, 'phase': 'near dwell', 'worst': 3.456, 'limit': 30.0, 'phi': 201.5, 'what': 'offset', 'r0_min': 34.567800000000005},
     'the chosen base radius r0 = 30.000 mm gives a pressure angle of 33.46 deg on the near dwell, 3.46 deg over the allowed 30 deg, largest at phi = 201.50 deg; the least r0 with the same offset is 34.568 mm'),
    ('cam.fail.chosen_pressure_none', {'r0': 30.0, 'theta': 33.456, 'phase': 'near dwell', 'worst': 3.456, 'limit': 30.0, 'phi': 201.5, 'what': 'centre distance'},
     'the chosen base radius r0 = 30.000 mm gives a pressure angle of 33.46 deg on the near dwell, 3.46 deg over the allowed 30 deg, largest at phi = 201.50 deg; no base radius with the same centre distance keeps the pressure angle within the allowed one'),
    ('gears.fail.invalid', {'m': 0.004, 'z1': 14, 'z2': 0},
     'invalid module or tooth numbers (m = 0.004, z = [14, 0])'),
    ('gears.fail.fillet', {'rho_f': 0.5, 'c': 0.25},
     'rack fillet rho_f* = 0.5 does not fit in the clearance c* = 0.25'),
    ('gears.fail.x_form', {'x': 'max'},
     "x must be two numbers or 'auto', not 'max'"),
    ('gears.fail.unknown_rule', {'rule': 'bogus'},
     "unknown shift rule 'bogus'"),
    ('gears.fail.no_mesh_angle', {'inv': -0.00123456789, 'xsum': -2.18765},
     'no mesh angle: inv alpha_w = -0.00123457 <= 0 (the shift sum x1 + x2 = -2.188 is too negative)'),
    ('gears.fail.root_radius', {'wheel': 1, 'rf': -0.00012345678},
     'wheel 1: root radius rf = -0.000123457 m is not positive'),
    ('gears.fail.no_tooth', {'wheel': 1, 'ra': 0.0201234567, 'rf': -0.00012345678},
     'wheel 1: the tip circle ra = 0.0201235 m is not above the root circle rf = -0.000123457 m (no tooth)'),
    ('planetary.fail.unknown_scheme', {'name': 'Z', 'known': 'A, B, C, D'},
     "unknown planetary scheme 'Z'; known: A, B, C, D"),
    ('planetary.fail.ratio_zero', {},
     'the required ratio must be a non-zero number'),
    ('planetary.fail.below_one', {'scheme': 'A', 'required': 0.8},
     'scheme A gives i_1H > 1 only (required 0.8)'),
    ('planetary.hint.z_max_below', {'z_max': 10, 'z_min': 17},
     'z_max = 10 is below z_min = 17'),
    ('planetary.hint.internal', {'scheme': 'B', 'z_int': 20},
     'scheme B has an internal wheel, which needs z >= 20: raise z_max'),
    ('planetary.hint.scheme_a', {'lo': 1.1333333, 'hi': 9.8235294},
     'scheme A gives 1 + z3/z1 only between 1.133 and 9.824 with these tooth limits: choose another scheme (B for larger ratios) or change z_min, z_max'),
    ('planetary.hint.general', {},
     'widen the tolerance or z_min..z_max, use fewer satellites (adjacency), or choose another scheme'),
    ('planetary.fail.none_found', {'scheme': 'C', 'required': 37.5, 'tol': 0.0123456, 'k': 3, 'z_min': 17, 'z_max': 150, 'hint': {'code': 'planetary.hint.general', 'params': {}, 'text': 'widen the tolerance or z_min..z_max, use fewer satellites (adjacency), or choose another scheme'}},
     'no tooth numbers for scheme C give i_1H = 37.5 within 0.0123 with 3 satellites (z in [17, 150]); widen the tolerance or z_min..z_max, use fewer satellites (adjacency), or choose another scheme'),
    ('drive_train.fail.sign', {'stages': '[0, 2]', 'u': -12.3456789},
     'the free stages [0, 2] cannot give the sign of u = -12.3457: external pairs turn the sense, internal pairs and schemes A, B keep it; make a pair internal/external or use scheme C or D'),
    ('drive_train.fail.pair_sign', {'i': 1, 'u': 3.456789, 'kind': 'internal'},
     'stage 1 (stages[1]): an internal pair cannot give u = 3.45679 (sign)'),
    ('drive_train.fail.pair_sign', {'i': 1, 'u': 3.456789, 'kind': 'external'},
     'stage 1 (stages[1]): an external pair cannot give u = 3.45679 (sign)'),
    ('drive_train.fail.pair_zmin', {'i': 0, 'u': 0.512345, 'z2': 9, 'zmin': 17},
     'stage 0 (stages[0], pair): u = 0.512345 needs z2 = 9 < z_min_external = 17; give the stage its own `ratio` (|u| >= 1) or its z'),
    ('drive_train.fail.pair_zmax', {'i': 0, 'u': 0.512345, 'z2': 301, 'zmax': 150},
     "stage 0 (stages[0], pair): u = 0.512345 needs z2 = 301 outside [5, z_max = 150]; raise z_max or give the stage's z or ratio"),
    ('drive_train.fail.below_one', {'i': 0, 'kind': 'A', 'u': 0.512345},
     'stage 0 (stages[0], planetary A) gives u > 1 only, its share is u = 0.512345: give the stage a `ratio`, or use scheme C or D'),
    ('drive_train.hint.nearest', {'near': 12.5, 'rel': 0.012500009213750137},
     'the nearest feasible ratio is 12.5 (+1.250%)'),
    ('drive_train.hint.none', {},
     'no tooth set meets the conditions at all'),
    ('drive_train.fail.none_found', {'i': 0, 'kind': 'C', 'u': 12.3456789, 'tol': 0.01, 'k': 3, 'near': {'code': 'drive_train.hint.nearest', 'params': {'near': 12.5, 'rel': 0.012500009213750137}, 'text': 'the nearest feasible ratio is 12.5 (+1.250%)'}, 'ext': 17, 'int': 85, 'sat': 18},
     'stage 0 (stages[0], planetary C): no tooth numbers give u = 12.3457 within tolerance 0.01 with 3 satellites; the nearest feasible ratio is 12.5 (+1.250%); relax `tolerance`, `satellites`, `z_max` or the tooth limits (z_min_external = 17, z_min_internal = 85, z_min_satellite_in_internal = 18), or give the stage its own `ratio`'),
    ('drive_train.fail.missed', {'u': 28.123456, 'err': -0.0345678, 'req': 29.0, 'tol': 0.01},
     'the chosen train gives u = 28.1235, -3.457% from the required 29 (tolerance 0.01); give the stages their own `ratio` or relax `tolerance`'),
    ('dof2.fail.too_long', {'rtol': 1e-08, 'nfev': 200000, 't': 0.123456, 't_stop': 2.0},
     'the motion is too long to integrate to rtol 1e-08: 200000 evaluations reached only t = 0.1235 s of 2 s (shorten t_end or turns, '
     'or check the speeds and moments given: a faster motion needs more steps)'),
    ('dof2.fail.integration', {'why': 'Required step size is less than spacing between numbers.'},
     'the integration failed: Required step size is less than spacing between numbers.'),
    ('dof2.fail.turns', {'turned': 2.34567, 'turns': 5.0, 't_stop': 2.0},
     'the rotor makes only 2.346 of the 5 turns within t_max = 2 s (give t_end, or a larger t_max or moment)'),
    ('dof2.fail.zero_duration', {},
     'the duration of the motion is zero'),
    ('dof2.fail.not_finite', {},
     'the motion is not finite (check the masses and the moments of inertia)'),
    ('dof2.fail.no_striker_inertia', {},
     'the striker has no inertia about O1 (m2*l_c^2 + J_C = 0): its motion is undetermined'),
    ('dof2.fail.singular_mass', {},
     'the mass matrix is singular at psi = 0 or 180 deg: the rotor has no moment of inertia about O and the striker is a point mass (give the rotor J or J_O, or the striker J)'),
    # the linkage's failures
    ('kinematics.fail.idle', {'links': ['lever', 'arm']},
     'link(s) lever, arm have an idle degree of freedom (a single pair); their position is undefined'),
    ('kinematics.fail.ppp', {'group': 'II(2,3)', 'links': ['rod', 'slider']},
     'group II(2,3) (links rod, slider): a PPP group has no definite position'),
    ('kinematics.fail.not_assembled', {'group': 'II(2,3)', 'links': ['rod', 'slider'], 'phi': 123.456789},
     'group II(2,3) (links rod, slider) could not be assembled at crank angle 123.457 deg: no solution of its loop-closure equations was found; check the dimensions'),
    ('kinematics.fail.limit_position', {'group': 'II(2,3)', 'links': ['rod', 'slider'], 'a': 95.1234567, 'b': 110.7654321},
     'group II(2,3) (links rod, slider) does not assemble for crank angles 95.1235..110.765 deg: the loop-closure equations of the group have no solution continuing the motion there (its links reach a limit position)'),
    ('kinematics.fail.never', {'group': 'II(2,3)', 'links': ['rod', 'slider']},
     'group II(2,3) (links rod, slider) does not assemble at any crank angle'),
    ('kinematics.reason.no_solution', {},
     'no solution of its loop-closure equations'),
    ('kinematics.reason.rrr_far', {'pa': 'A', 'pb': 'D', 'pc': 'B', 'd': 0.51234567, 'la': 0.2, 'lb': 0.25, 'link_a': 'rod', 'link_b': 'rocker'},
     '|AD| = 0.512346 m > |AB| + |BD| = 0.2 + 0.25 m (links rod and rocker cannot reach)'),
    ('kinematics.reason.rrr_near', {'pa': 'A', 'pb': 'D', 'pc': 'B', 'd': 0.0123, 'la': 0.2, 'lb': 0.25},
     '|AD| = 0.0123 m < ||AB| - |BD|| = |0.2 - 0.25| m'),
    ('kinematics.reason.rrp_short', {'p': 'A', 'q': 'B', 'l': 0.08, 'link': 'rod'},
     'the distance from A to the line along which B must move exceeds |AB| = 0.08 m (link rod is too short)'),
    ('kinematics.reason.rpr_offset', {'s': 'slider', 'g': 'rocker', 'pivot': 'C', 'other': 'A'},
     'the guide of the prismatic pair slider/rocker must keep its offset from the pivot C, which is closer to A than that offset'),
    ('kinematics.reason.parallel_guides', {},
     'the guides of the group are parallel (the prismatic pairs lock)'),
    ('kinematics.fail.intervals', {'group': 'II(2,3)', 'links': ['rod', 'slider'], 'intervals': [[95.1234567, 110.7654321], [250.0, 265.5]], 'reason': {'code': 'kinematics.reason.rrr_far', 'params': {'pa': 'A', 'pb': 'D', 'pc': 'B', 'd': 0.51234567, 'la': 0.2, 'lb': 0.25, 'link_a': 'rod', 'link_b': 'rocker'}, 'text': '|AD| = 0.512346 m > |AB| + |BD| = 0.2 + 0.25 m (links rod and rocker cannot reach)'}},
     'group II(2,3) (links rod, slider) does not assemble for crank angles 95.123457..110.765432, 250.000000..265.500000 deg: |AD| = 0.512346 m > |AB| + |BD| = 0.2 + 0.25 m (links rod and rocker cannot reach)'),
    ('kinematics.reason.at', {'phi': 180.0, 'reason': {'code': 'kinematics.reason.rrr_near', 'params': {'pa': 'A', 'pb': 'D', 'pc': 'B', 'd': 0.05, 'la': 0.3, 'lb': 0.22}, 'text': '|AD| = 0.05 m < ||AB| - |BD|| = |0.3 - 0.22| m'}},
     'at 180 deg, |AD| = 0.05 m < ||AB| - |BD|| = |0.3 - 0.22| m'),
    ('kinematics.reason.each', {'items': [{'code': 'kinematics.reason.at', 'params': {'phi': 180.0, 'reason': {'code': 'kinematics.reason.no_solution', 'params': {}, 'text': 'no solution of its loop-closure equations'}}, 'text': 'at 180 deg, no solution of its loop-closure equations'}, {'code': 'kinematics.reason.at', 'params': {'phi': 0.0, 'reason': {'code': 'kinematics.reason.no_solution', 'params': {}, 'text': 'no solution of its loop-closure equations'}}, 'text': 'at 0 deg, no solution of its loop-closure equations'}]},
     'at 180 deg, no solution of its loop-closure equations; at 0 deg, no solution of its loop-closure equations'),
    ('input.script_note', {'cyr': '\u041e1', 'lat': 'O1', 'letters': '\u041e'},
     "'\u041e1' is typed with the Cyrillic \u041e, 'O1' with Latin letters: type the names alike"),
    ('structure.fail.point_hint_script', {'point': 'A', 'note': {'code': 'input.script_note', 'params': {'cyr': '\u0410', 'lat': 'A', 'letters': '\u0410'}, 'text': "'\u0410' is typed with the Cyrillic \u0410, 'A' with Latin letters: type the names alike"}},
     " — did you mean A? ('\u0410' is typed with the Cyrillic \u0410, 'A' with Latin letters: type the names alike)"),
    ('input.point_not_ground_script', {'point': 'O', 'link': 'crank', 'ground': '\u041e', 'note': {'code': 'input.script_note', 'params': {'cyr': '\u041e', 'lat': 'O', 'letters': '\u041e'}, 'text': "'\u041e' is typed with the Cyrillic \u041e, 'O' with Latin letters: type the names alike"}},
     "point 'O' of link 'crank' is on no other link and is no ground point: did you mean the ground point '\u041e'? ('\u041e' is typed with the Cyrillic \u041e, 'O' with Latin letters: type the names alike)"),
    ('input.no_link_script', {'name': 'cr\u0430nk', 'hint': 'crank', 'note': {'code': 'input.script_note', 'params': {'cyr': 'cr\u0430nk', 'lat': 'crank', 'letters': '\u0430'}, 'text': "'cr\u0430nk' is typed with the Cyrillic \u0430, 'crank' with Latin letters: type the names alike"}},
     "no link named 'cr\u0430nk'; did you mean 'crank'? ('cr\u0430nk' is typed with the Cyrillic \u0430, 'crank' with Latin letters: type the names alike)"),
    ('positions.fail.output_turns', {'link': 'slider'},
     "the output link 'slider' has no extreme positions (it turns fully), so stroke-based loads cannot be placed"),
    ('positions.fail.load_no_extremes', {'link': 'slider'},
     "link 'slider' carries a load over its stroke but has no extreme positions, so the load cannot be placed"),
    ('positions.fail.no_zero', {'link': 'slider'},
     "the output link 'slider' has no extreme positions (it turns fully or stands still); give positions.zero as a crank angle in degrees"),
    ('kinetostatics.fail.no_group', {'links': "['arm', 'lever']"},
     "links ['arm', 'lever'] belong to no Assur group"),
    ('kinetostatics.fail.indeterminate', {'links': "['rod', 'slider']", 'equations': 6, 'unknowns': 7},
     "group ['rod', 'slider'] is not statically determinate (6 equations, 7 unknown reaction components)"),
    ('kinetostatics.fail.not_square', {'equations': 9, 'unknowns': 10},
     'the equilibrium system is not square (9 equations, 10 unknowns): W must be 1 with no passive constraints'),
    ('kinetostatics.fail.singular_everywhere', {},
     'the equilibrium equations are singular at every position (passive constraints?)'),
    ('loads.fail.no_positions', {},
     'loads given over a stroke need the positions (extreme positions)'),
    ('loads.fail.point_still', {'k': 2, 'link': 'slider'},
     "the point of load 2 on 'slider' does not move: give `direction`"),
    ('flywheel.fail.drive_speed', {'value': -5.23},
     'the drive speed must be positive (got -5.23)'),
    ('flywheel.fail.cycle', {'value': 540.0},
     'the cycle must be 360 or 720 deg (got 540.0)'),
    ('flywheel.fail.resolution', {'value': 1},
     'resolution must be at least 2 (got 1)'),
    ('flywheel.fail.method', {'method': 'simpson'},
     "unknown method 'simpson'"),
    ('flywheel.fail.J_not_finite', {'link': 'rod'},
     "reduced moment of inertia of 'rod' is not finite"),
    ('flywheel.fail.J_negative', {'link': 'rod'},
     "reduced moment of inertia of 'rod' is negative"),
    ('flywheel.fail.eps_not_finite', {},
     'angular acceleration of the crank is not finite'),
    ('flywheel.fail.nodes', {},
     'the cycle needs at least two nodes with one moment each'),
    ('flywheel.fail.M_not_finite', {},
     'the reduced moment of the loads is not finite'),
    ('flywheel.fail.nodes_order', {},
     'cycle nodes must be non-decreasing over a positive span'),
    ('flywheel.fail.works_not_finite', {},
     'the works of the loads over the cycle are not finite'),
    ('flywheel.fail.constant', {'kind': 'torque'},
     "unknown constant moment kind 'torque'"),
    ('flywheel.fail.mean_speed', {'value': 0.0},
     'the mean speed must be positive (got 0.0)'),
    ('flywheel.fail.delta', {'value': 1.5},
     'delta must lie in (0, 1) (got 1.5)'),
    ('flywheel.fail.energy_not_finite', {},
     'kinetic energy change or reduced inertia is not finite'),
    ('flywheel.fail.J_not_positive', {},
     'the total reduced moment of inertia is not positive over the cycle (give link masses / moments of inertia or a flywheel)'),
    ('flywheel.fail.stops', {},
     'the machine stops within the cycle at this mean speed: the flywheel is far too light (speed fluctuation >= 200 %)'),
    ('flywheel.fail.bracket', {},
     'could not bracket the flywheel for the required delta'),
    ('flywheel.fail.shape', {'shape': 'cone'},
     "unknown flywheel shape 'cone'"),
    ('flywheel.fail.kind_not_finite', {'kind': 'resistance'},
     "the reduced moment of the 'resistance' loads is not finite"),
]


def _fields(template: str) -> dict[str, set[str]]:
    """{placeholder name: its format specs} of a template."""
    out: dict[str, set[str]] = {}
    for _lit, name, spec, _conv in string.Formatter().parse(template):
        if name is not None:
            out.setdefault(name, set()).add(spec or "")
    return out


@pytest.mark.parametrize("code,params,text", ENGLISH, ids=[f"{c}-{i}" for i, (c, _, _) in enumerate(ENGLISH)])
def test_english_text_unchanged(code, params, text):
    m = Message(code, **params)
    assert m == text
    assert (m.code, m.params) == (code, params)
    assert m.to_dict() == {"code": code, "params": params, "text": text}


def test_every_english_code_has_a_pinned_text():
    assert {c for c, _, _ in ENGLISH} == set(catalogue("en")["messages"]) - {PLAIN}


def _counted_noun(spec: str, lang: str) -> bool:
    """A count's noun in its forms, {n:|form|form...} (the count and the noun), or {list:#form|form...}
    (the noun alone, its form by the list's length): as many as the language's rule has (numbers
    catalogue `format.plural`: one and other in English, one, few and many in ru/uk)."""
    from tmm_cli import locales
    if not spec.startswith(("|", "#")):
        return False
    want = {"one_other": 2, "one_few_many": 3}[locales.of("numbers", "format", lang)["plural"]]
    return len(spec[1:].split("|")) == want and all(f.strip() for f in spec[1:].split("|"))


@pytest.mark.parametrize("lang", OTHERS)
def test_catalogue_complete(lang):
    """Every code of en.yaml in the catalogue with the same placeholders; a spec is the
    English one or names a word table of the language, and every table has the same words
    in every language."""
    en, cat = catalogue("en")["messages"], catalogue(lang)
    assert set(cat["messages"]) == set(en)
    for code, template in en.items():
        want, got = _fields(template), _fields(cat["messages"][code])
        assert set(got) == set(want), (lang, code)
        for name, specs in got.items():
            for spec in specs:
                assert (spec in want[name] or spec in cat["terms"] or spec in messages.SPECS
                        or _counted_noun(spec, lang)), (lang, code, name, spec)
    for other in OTHERS:
        terms = catalogue(other)["terms"]
        assert set(terms) == set(cat["terms"])
        for name, table in cat["terms"].items():
            assert set(table) == set(terms[name]), (lang, other, name)


def _codes(expr) -> list[str]:
    """The code literals of a Message's first argument: a string, or a conditional of them."""
    if isinstance(expr, ast.Constant) and isinstance(expr.value, str):
        return [expr.value]
    if isinstance(expr, ast.IfExp):
        return _codes(expr.body) + _codes(expr.orelse)
    return []


def _emitted_codes() -> dict[str, str]:
    """{code: file} of every Message(...) made in tmm_cli (both branches of a conditional)."""
    found = {}
    for path in PKG.rglob("*.py"):
        if path.parent.name == "messages":
            continue
        tree = ast.parse(path.read_text(encoding="utf-8"))
        for node in ast.walk(tree):
            if isinstance(node, ast.Call) and getattr(node.func, "id", None) == "Message" and node.args:
                codes = _codes(node.args[0])
                if not codes and path.name == "task.py" and isinstance(node.args[0], ast.JoinedStr):
                    continue        # Message(f"input.{kind}") of _PYDANTIC_CODES (counted by the caller)
                assert codes, f"{path}:{node.lineno}: a Message code must be a literal (found by this test)"
                for c in codes:
                    found[c] = str(path.relative_to(ROOT))
    return found


def test_every_emitted_code_is_catalogued_and_every_code_emitted():
    from tmm_cli.task import _PYDANTIC_CODES   # pydantic's error types: input.<type>
    emitted = _emitted_codes()
    emitted.update({f"input.{kind}": "tmm_cli/task.py" for kind in _PYDANTIC_CODES})
    codes = set(catalogue("en")["messages"])
    assert not set(emitted) - codes, {c: emitted[c] for c in set(emitted) - codes}
    assert not codes - {PLAIN} - set(emitted), codes - {PLAIN} - set(emitted)


def _stage_modules():
    for pkg in STAGES:
        yield from sorted((PKG / pkg).rglob("*.py"))


def _docstrings(tree) -> set[int]:
    ids = set()
    for node in ast.walk(tree):
        if isinstance(node, (ast.Module, ast.ClassDef, ast.FunctionDef, ast.AsyncFunctionDef)):
            body = node.body
            if body and isinstance(body[0], ast.Expr) and isinstance(body[0].value, ast.Constant):
                ids.add(id(body[0].value))
    return ids


def test_no_language_literal_in_stage_modules():
    """Stage modules hold no Russian or Ukrainian text (a docstring may cite a textbook by
    its title); what users read in another language comes from the catalogues."""
    cyr = re.compile(r"[\u0400-\u04FF]")
    bad = []
    files = list(_stage_modules())
    assert len(files) > 30
    for path in files:
        tree = ast.parse(path.read_text(encoding="utf-8"))
        docs = _docstrings(tree)
        for node in ast.walk(tree):
            if (isinstance(node, ast.Constant) and isinstance(node.value, str) and id(node) not in docs
                    and cyr.search(node.value)):
                bad.append(f"{path.relative_to(ROOT)}:{node.lineno}: {node.value[:40]}")
            if isinstance(node, (ast.Attribute, ast.Name, ast.arg, ast.keyword)):
                name = getattr(node, "attr", None) or getattr(node, "id", None) or getattr(node, "arg", None)
                if name and re.search(r"_(ru|uk)$", name):
                    bad.append(f"{path.relative_to(ROOT)}:{getattr(node, 'lineno', '?')}: {name}")
    assert not bad, bad


def _english_words(text: str, params: dict) -> set[str]:
    """Words of plain English letters in ``text``: not a symbol or a task-file name (with
    ``_``, ``.`` or in backticks, such as near_singular, `flywheel.resolution`, J_n), not a
    parameter's own value (a link's name), not the unit the task file would take (rpm), nor a proper name (YAML, Moodle)."""
    values = {w for v in params.values() for w in re.findall(r"\w+", str(v))}
    out = set()
    for tok in text.split():
        core = tok.strip("()[],;:'\"«»")
        if "_" in core or "." in core or "`" in tok:
            continue
        if core.isascii() and core.isalpha() and len(core) >= 3 and core not in values | {"rpm", "YAML", "Moodle"}:
            out.add(core)
    return out


@pytest.mark.parametrize("lang", OTHERS)
def test_translations_leave_no_english(lang):
    for code, params, text in ENGLISH:
        out = render(code, params, lang)
        assert out != text, (lang, code)
        assert not _english_words(out, params), (lang, code, out)
        terms = catalogue(lang)["terms"]               # a word table translates a parameter
        by_terms = any(sp in terms for sps in _fields(catalogue(lang)["messages"][code]).values() for sp in sps)
        nested = any(isinstance(v, dict) or (isinstance(v, list) and v and isinstance(v[0], dict))
                     for v in params.values())                              # a message inside a message
        formula = not re.search(r"[A-Za-z]{3,}", text)                      # symbols and units only
        assert _english_words(text, params) or code == "text" or by_terms or nested or formula  # can fail
        if lang == "uk":
            assert not set(out) & set("ыэъёЫЭЪЁ"), (code, out)


def test_plain_string_and_unknown_code():
    """A warning given as a plain string keeps its text in every language; an entry with a
    code this version does not know (a newer results.json) shows its English text."""
    d = as_dict("a free-text warning")
    assert d == {"code": PLAIN, "params": {"text": "a free-text warning"}, "text": "a free-text warning"}
    assert localize(d, "ru") == "a free-text warning"
    assert localize({"code": "x.unknown", "params": {}, "text": "new"}, "uk") == "new"
    assert localize({"code": "cam.soft_impact", "params": {"phi": None, "where": "rise"}, "text": "t"}, "ru") == "t"
    with pytest.raises(KeyError):
        Message("x.unknown")


def test_render_list_reads_messages_else_warnings():
    m = Message("dof2.rotor_reverses")
    assert render_list({"warnings": [str(m)], "messages": [m.to_dict()]}, "uk") == \
        ["машина з двома ступенями рухомості: ротор змінює напрямок обертання"]   # the glossary's term
    # results.json written before messages existed: the English texts as they are
    assert render_list({"warnings": ["old text"]}, "ru") == ["old text"]
    assert render_list({}, "ru") == []


def test_message_is_plain_data():
    import numpy as np
    m = Message("gears.undercut", wheel=np.int64(2), z=15, x=np.float64(0.0), x_min=np.float64(0.1176))
    assert type(m.params["wheel"]) is int and type(m.params["x"]) is float
    back = pickle.loads(pickle.dumps(m))
    assert back == m and back.code == m.code and back.params == m.params
    assert Message("cam.profile_corners", phis=(0.0, np.float64(120.0))).params == {"phis": [0.0, 120.0]}


def test_catalogues_are_the_report_languages():
    """A language is one folder of catalogues (tmm_cli/locales/<lang>/, its messages.yaml
    among them); the folders found are the report's languages."""
    from tmm_cli import locales
    from tmm_cli.report import i18n

    assert sorted(p.parent.name for p in locales.DIR.glob("*/messages.yaml")) == sorted(LANGS)
    assert LANGS == i18n.LANGS == locales.LANGS


@pytest.fixture(scope="module")
def warned_reports(tmp_path_factory):
    """The Russian and Ukrainian reports of examples whose warnings cover the cam's
    phases and swing sense and the gears' undercut."""
    import tmm_cli
    from tmm_cli.report import render_html

    out = {}
    for name in ("cam_rocker", "cam_offset", "gears_zero"):
        task = tmm_cli.load_task(ROOT / "tasks" / f"{name}.yaml")
        res = tmm_cli.run(task, kinematics_curve=0)
        d = tmp_path_factory.mktemp(name)
        out[name] = (res, {lang: render_html(res, task, d, lang)[0] for lang in OTHERS})
    return out


@pytest.mark.parametrize("lang", OTHERS)
def test_translated_reports_have_no_english_warning(warned_reports, lang):
    from html import unescape
    for name, (res, html) in warned_reports.items():
        assert res["warnings"] and [m["text"] for m in res["messages"]] == res["warnings"]
        sec = re.search(r'<section class="section" id="warnings">(.*?)</section>', html[lang], re.S)
        items = [unescape(x).strip() for x in re.findall(r"<li>(.*?)</li>", sec.group(1), re.S)]
        assert len(items) == len(res["messages"]), name
        for item, m in zip(items, res["messages"]):
            assert item == render(m["code"], m["params"], lang)
            assert not _english_words(item, m["params"]), (name, lang, item)
            assert m["text"] not in html[lang]


def test_quantity_words_are_the_units_words():
    """The English `quantity` table renders a field's expected quantity exactly as the unit
    reader names it (tmm_cli/units.py KINDS), and every language has every quantity."""
    from tmm_cli.units import KINDS
    assert catalogue("en")["terms"]["quantity"] == {kind: words for kind, (_, words) in KINDS.items()}
    for lang in OTHERS:
        assert set(catalogue(lang)["terms"]["quantity"]) == set(KINDS)


def test_task_error_coded_is_its_text_in_every_language(tmp_path):
    """An invalid task's coded message is exactly its English text (stderr), and renders in
    Russian and Ukrainian with the same file, line and field; an issue no check codes
    stays English inside the translated frame."""
    from tmm_cli.errors import TaskError
    f = tmp_path / "t.yaml"
    f.write_text("schema: tmm/1\ndrive: {link: crank, speed: 90 rmp, direction: clockwise}\n", encoding="utf-8")
    with pytest.raises(TaskError) as info:
        __import__("tmm_cli").load_task(f)
    coded = info.value.coded()
    assert coded == info.value.render() == str(info.value)
    ru = localize(coded.to_dict(), "ru").splitlines()
    uk = localize(coded.to_dict(), "uk").splitlines()
    assert ru[0].startswith(f"{f}:2:") and "поле «drive." in ru[0]
    assert any("неизвестная единица измерения «rmp» в «90 rmp»; ожидается угловая скорость" in x for x in ru)
    assert any("допустимые значения: 'ccw' или 'cw'; задано 'clockwise'" in x for x in ru)
    assert any("невідома одиниця вимірювання «rmp» у «90 rmp»" in x for x in uk)
    plain = TaskError("x", file="a.yaml", issues=[("f", 3, None, "a check with no code")])
    assert localize(plain.coded().to_dict(), "ru") == "a.yaml:3: поле «f»: a check with no code"


def test_crank_angle_intervals_are_data_formatted_per_language():
    """A group's failing intervals are [from, to] pairs in degrees: the English text keeps
    its six decimals (stderr, results.json); Russian and Ukrainian show φ = a…b° to 0.1°,
    finer where an interval is narrower than the rounding, separated by semicolons (a comma
    between two numbers would read as a decimal one); a list of names keeps its commas."""
    reason = Message("kinematics.reason.no_solution")
    m = Message("kinematics.fail.intervals", group="II(2,3)", links=["rod", "ram"], reason=reason,
                intervals=[[37.46, 52.14], [350.0, 10.25], [120.012, 120.048]])
    assert m.params["intervals"] == [[37.46, 52.14], [350.0, 10.25], [120.012, 120.048]]
    assert "crank angles 37.460000..52.140000, 350.000000..10.250000, 120.012000..120.048000 deg:" in m
    ru = render(m.code, m.params, "ru")
    assert "при углах кривошипа φ = 37,5…52,1°; 350,0…10,2°; 120,01…120,05°: уравнения" in ru   # decimal comma
    assert "(звенья rod, ram)" in ru
    assert "φ = 37,5…52,1°" in render(m.code, m.params, "uk")


def test_a_noun_takes_the_form_of_its_lists_length():
    """"at crank angle(s)" in ru and uk: the noun in the form of the number of angles, without the
    number ("при угле кривошипа 0°", "при углах кривошипа 0; 180°"); English as written."""
    for angles, ru, uk in (([90.0], "при угле кривошипа 90°", "за кута кривошипа 90°"),
                           ([0.0, 180.0], "при углах кривошипа 0; 180°", "за кутів кривошипа 0; 180°"),
                           ([1.0, 2.0, 3.0, 4.0, 5.0], "при углах кривошипа 1; 2; 3; 4; 5°", "за кутів кривошипа 1; 2")):
        m = Message("kinematics.singular_continuity", group="II(2,3)", links=["a", "b"], angles=angles, delta=1e-6)
        assert ru in render(m.code, m.params, "ru") and uk in render(m.code, m.params, "uk")
        assert "at crank angle(s) " in m
    from tmm_cli.messages import _Formatter
    assert _Formatter({}, "en").format_field(["x"], "#angle|angles") == "angle"
    assert _Formatter({}, "en").format_field(["x", "y"], "#angle|angles") == "angles"


def test_number_lists_in_the_decimal_comma_languages():
    """A list of numbers in a message: ", " in English, "; " in ru and uk (0, 180 would read as
    0,180); an interval's ends ".." in English, "…" in ru and uk."""
    m = Message("kinematics.singular_continuity", group="II(2,3)", links=["coupler", "rocker"], angles=[0.0, 180.0],
                delta=1e-6)
    assert "at crank angle(s) 0, 180 deg" in m
    ru = render(m.code, m.params, "ru")
    assert "0; 180°" in ru and "(звенья coupler, rocker)" in ru
    from tmm_cli.messages import _Formatter
    f = _Formatter({}, "uk")
    assert f.format_field([[45.0, 105.0], 7.5], "g") == "45…105; 7,5"
    assert _Formatter({}, "en").format_field([[45.0, 105.0], 7.5], "g") == "45..105, 7.5"


@pytest.mark.parametrize("lang", LANGS)
def test_every_short_form_is_a_messages_code_with_its_placeholders(lang):
    """The short forms under a change point (the catalogue's ``folded`` table, messages.grouped):
    every language has each of English's, each the short form of a catalogued code, naming no
    parameter the code's message lacks; and each takes a list of positions (the noun in the form
    the list's length takes: English "position 12", "positions 6, 12")."""
    fields = string.Formatter()
    en = catalogue("en")
    short = catalogue(lang)["folded"]
    assert set(short) == set(en["folded"]) and short
    for code, template in short.items():
        assert code in en["messages"], code
        names = {f for _, f, _, _ in fields.parse(template) if f}
        assert names <= {f for _, f, _, _ in fields.parse(en["messages"][code]) if f}, (lang, code)
    from tmm_cli.messages import folded
    one = folded({"code": "kinetostatics.no_kinematics", "params": {"position": [12], "balancing": "force"}}, lang)
    two = folded({"code": "kinetostatics.no_kinematics", "params": {"position": [6, 12], "balancing": "force"}}, lang)
    assert "12" in one and "6" not in one and "6" in two and "12" in two
    if lang == "en":
        assert (one, two) == ("kinetostatics, position 12: no balancing force or reactions",
                              "kinetostatics, positions 6, 12: no balancing force or reactions")


@pytest.mark.parametrize("lang", ["ru", "uk"])
@pytest.mark.parametrize("code, params", [("answers.not_mapping", {}), ("input.unit_expected", {"kind": "length"})])
def test_a_yaml_type_is_named_after_a_colon_in_ru_uk(lang, code, params):
    """"got a list" as "\u0437\u0430\u0434\u0430\u043d\u043e: \u0441\u043f\u0438\u0441\u043e\u043a": the impersonal
    "\u0437\u0430\u0434\u0430\u043d\u043e" before a masculine or feminine noun (\u0441\u043f\u0438\u0441\u043e\u043a,
    \u0442\u0430\u0431\u043b\u0438\u0446\u0430, \u0442\u0435\u043a\u0441\u0442) does not agree in Russian and wants
    the accusative (\u0442\u0430\u0431\u043b\u0438\u0446\u044e) in Ukrainian: the type is named after a colon."""
    for got in ("list", "dict", "str", "bool", "NoneType"):
        word = catalogue(lang)["terms"]["yaml_type"][got]
        assert f"\u0437\u0430\u0434\u0430\u043d\u043e: {word}" in render(code, {**params, "got": got}, lang), (got, lang)


@pytest.mark.parametrize("lang, text", [("ru", "\u043f\u043e \u043c\u043e\u0434\u0443\u043b\u044e \u0432\u0435\u0440\u043d\u043e"),
                                        ("uk", "\u0437\u0430 \u043c\u043e\u0434\u0443\u043b\u0435\u043c \u043f\u0440\u0430\u0432\u0438\u043b\u044c\u043d\u043e")])
def test_a_wrong_signs_note_says_the_magnitude_is_right_not_the_quantity(lang, text):
    """"right magnitude, wrong sign": the modulus (\u043c\u043e\u0434\u0443\u043b\u044c) is right; "\u0432\u0435\u043b\u0438\u0447\u0438\u043d\u0430"
    is the check table's word for the quantity itself (\u043d\u0435\u0438\u0437\u0432\u0435\u0441\u0442\u043d\u0430\u044f
    \u0432\u0435\u043b\u0438\u0447\u0438\u043d\u0430), so "\u0432\u0435\u043b\u0438\u0447\u0438\u043d\u0430 \u0432\u0435\u0440\u043d\u0430" read as the quantity being right."""
    assert render("answers.note_sign", {}, lang).startswith(text)
