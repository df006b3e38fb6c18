#!/usr/bin/env python3
"""Measures, in beltsim's runs of the paper's three scripts, the points the paper states for its
Figs 8-13, 15-18 and 20-23, and writes them as tables into docs/paper.md.

    python3 media/paper_values.py RUNS PAGE

RUNS holds the three runs as media/make_media.sh writes them (RUNS/paper_dry, RUNS/paper_wet,
RUNS/automotive_wet, each with timeseries.csv and parameters.csv). PAGE is docs/paper.md: each
block between '<!-- paper_values figNN -->' and '<!-- /paper_values -->' is replaced by the table of
figure NN; the rest of the page is left as it is. Python 3 standard library only.

Every number in the 'beltsim' column is measured here; the 'paper' column quotes the paper (the
figure it is about, and the page section). Signs are the CSV's: counter-clockwise positive, so the
clockwise pulleys' speeds and the driving torques are negative; the friction force is positive
where the pulley pulls the belt forward, the slip velocity is the belt's speed minus the rim's.

Where the selected element is: the CSV has its normal force, so its contacts are the intervals
with N > 0 (breaks shorter than MERGE_GAP, where the element lifts for a moment within one wrap,
are bridged); they are given to the pulleys in the route's order (the order of the pulley rows
of parameters.csv, the direction of travel), starting from the pulley the probe starts on or
first meets. A check of that reading: on the driving pulley the mean friction of each contact
after the first lap pulls the belt forward (> 0); on the driven pulley of the two-pulley drives
it holds the belt back (< 0). A run where this fails stops the script: its contacts need a look.
"""
import csv
import math
import os
import re
import sys

MERGE_GAP = 0.004  # s: shorter breaks of contact are lift-offs within one wrap
DV = 1e-5          # m/s: the friction law's slip band (Δv, paper §3)
DV_TEXT = '1e-5 m/s'


# --- reading ---------------------------------------------------------------------------------------

class Run:
    def __init__(self, folder, first_pulley, drive_pulley):
        self.name = os.path.basename(folder.rstrip('/'))
        with open(os.path.join(folder, 'timeseries.csv'), newline='') as f:
            rows = csv.reader(f)
            head = next(rows)
            cols = [[] for _ in head]
            for row in rows:
                for k, v in enumerate(row):
                    cols[k].append(float(v) if v.strip() else math.nan)
        self.c = dict(zip(head, cols))
        self.t = self.c['t']
        self.dt = self.t[1] - self.t[0]
        self.p = {}
        self.route = []
        with open(os.path.join(folder, 'parameters.csv'), newline='') as f:
            for row in csv.reader(f):
                if row and row[0] != 'name':
                    self.p[row[0]] = row[1]
                    m = re.fullmatch(r'pulley\.(.+)\.wrap_angle', row[0])
                    if m:
                        self.route.append(m.group(1))
        self.drive = drive_pulley
        self.contacts = self._contacts(first_pulley)

    def col(self, name):
        return self.c[name]

    def idx(self, t):
        return min(range(len(self.t)), key=lambda i: abs(self.t[i] - t))

    def at(self, name, t):
        return self.c[name][self.idx(t)]

    def window(self, name, t0, t1):
        return [(ti, y) for ti, y in zip(self.t, self.c[name]) if t0 - 1e-9 <= ti <= t1 + 1e-9 and y == y]

    def mean(self, name, t0, t1):
        w = self.window(name, t0, t1)
        return sum(y for _, y in w) / len(w)

    def extreme(self, name, t0, t1, key=abs):
        """(t, y) of the sample with the largest key(y) in [t0, t1]"""
        return max(self.window(name, t0, t1), key=lambda p: key(p[1]))

    def _contacts(self, first):
        n = self.c['probe.normal_force']
        spans, on = [], None
        for i, v in enumerate(n):
            if v > 0 and on is None:
                on = i
            elif not v > 0 and on is not None:
                spans.append([on, i - 1])
                on = None
        if on is not None:
            spans.append([on, len(n) - 1])
        merged = []
        for a, b in spans:
            if merged and self.t[a] - self.t[merged[-1][1]] < MERGE_GAP:
                merged[-1][1] = b
            else:
                merged.append([a, b])
        k0 = self.route.index(first)
        out = []
        for k, (a, b) in enumerate(merged):
            pulley = self.route[(k0 + k) % len(self.route)]
            out.append({'pulley': pulley, 'i0': a, 'i1': b, 't0': self.t[a], 't1': self.t[b],
                        'complete': a > 0 and b < len(self.t) - 1})
        self._check(out)
        return out

    def _check(self, contacts):
        f = self.c['probe.friction_force']
        lap = 0.25  # s: the first lap, while the drive starts from rest, is not checked
        for ct in contacts:
            if ct['t0'] < lap or not ct['complete']:
                continue
            mean_f = sum(f[i] for i in range(ct['i0'], ct['i1'] + 1) if f[i] == f[i]) / (ct['i1'] - ct['i0'] + 1)
            wrong = (ct['pulley'] == self.drive and mean_f <= 0) or \
                    (len(self.route) == 2 and ct['pulley'] != self.drive and mean_f >= 0)
            if wrong:
                sys.exit(f"paper_values: {self.name}: the contact at {ct['t0']:.3f}-{ct['t1']:.3f} s, read as the "
                         f"{ct['pulley']}, has mean friction {mean_f:.1f} N: the route-order reading of the probe's "
                         f"contacts does not hold; look at the run")

    def on(self, pulley, after=0.0, complete=True):
        return [c for c in self.contacts if c['pulley'] == pulley and c['t0'] >= after and (c['complete'] or not complete)]

    def where(self, t):
        """the pulley the probe touches at t, or 'span <a>-<b>' between the contacts around it"""
        prev = None
        for ct in self.contacts:
            if ct['t0'] <= t <= ct['t1']:
                return ct['pulley']
            if ct['t0'] > t:
                nxt = ct['pulley']
                if prev is None:
                    prev = self.route[(self.route.index(nxt) - 1) % len(self.route)]
                return f'the {prev}–{nxt} span'
            prev = ct['pulley']
        return 'a span'

    def samples(self, ct, name):
        y = self.c[name]
        return [y[i] for i in range(ct['i0'], ct['i1'] + 1) if y[i] == y[i]]

    def rim(self, pulley, i):
        return abs(self.c[pulley + '.omega'][i]) * float(self.p[f'pulley.{pulley}.radius'])

    def belt_speed(self, ct):
        """mean speed of the element along the belt in a contact: slip + the rim's speed"""
        s = self.c['probe.slip_velocity']
        v = [s[i] + self.rim(ct['pulley'], i) for i in range(ct['i0'], ct['i1'] + 1) if s[i] == s[i]]
        return sum(v) / len(v)


# --- formatting ------------------------------------------------------------------------------------

def num(x, digits=3):
    """x to `digits` significant digits (at least one decimal below 10), '−' as the minus sign"""
    if x == 0:
        return '0'
    decimals = max(0, digits - 1 - int(math.floor(math.log10(abs(x)))))
    return f'{x:.{decimals}f}'.replace('-', '−')


def ms(t):
    return f'{t:.3f}'


def interval(ct):
    return f"{ms(ct['t0'])}–{ms(ct['t1'])} s"


def table(rows):
    out = ['| point | paper | beltsim | how beltsim\'s value is measured |', '|---|---|---|---|']
    cell = lambda text: text.replace('|', '\\|')  # a '|' of |x| would end the cell
    out += ['| ' + ' | '.join(cell(x) for x in row) + ' |' for row in rows]
    return '\n'.join(out)


# --- the figures -----------------------------------------------------------------------------------

def steady_from(run, name, t_end, tol):
    """first time after which |y - mean(0.9..1 s)| stays within tol·|mean|"""
    final = run.mean(name, 0.9, t_end)
    t_from = None
    for ti, y in zip(run.t, run.c[name]):
        if abs(y - final) > tol * abs(final):
            t_from = None
        elif t_from is None:
            t_from = ti
    return t_from


def dry_figures(d):
    out = {}
    w1, w2 = d.mean('driver.omega', 0.9, 1.0), d.mean('driven.omega', 0.9, 1.0)
    out['08'] = table([
        ('driving pulley ω1 at the end', '68.5 rad/s, "after about 0.6 s … remained constant" (Fig. 8, §3)',
         f'{num(w1, 4)} rad/s', 'mean of `driver.omega` over 0.9–1 s'),
        ('driven pulley ω2 at the end', '"about 68.0 rad/s" (Fig. 8, §3)', f'{num(w2, 4)} rad/s',
         'mean of `driven.omega` over 0.9–1 s'),
        ('slip |ω1| − |ω2|', '"about 0.5 rad/s" (Fig. 8, §3)', f'{num(abs(w1) - abs(w2), 2)} rad/s',
         "difference of the two means' magnitudes"),
        ('ω1 when the torque ramp ends (0.3 s)', '"hasn\'t stabilized yet" (Fig. 8, §3)',
         f"{num(d.at('driver.omega', 0.3))} rad/s ({100 * d.at('driver.omega', 0.3) / w1:.0f} % of the end value)",
         '`driver.omega` at t = 0.3 s'),
        ('ω1 steady from', '"after about 0.6 s" (Fig. 8, §3)',
         f"{ms(steady_from(d, 'driver.omega', 1.0, 0.005))} s",
         '`driver.omega` within 0.5 % of its 0.9–1 s mean from then on'),
    ])
    out['09'] = table([
        ('driving torque Md1', '70 N·m from 0.3 s (Fig. 7a, input)', f"{num(d.mean('driver.torque', 0.9, 1.0))} N·m",
         'mean of `driver.torque` over 0.9–1 s (the input ramp)'),
        ('resistance torque Md2', '"reaches value about 65 Nm" (Fig. 9, §3)',
         f"{num(d.mean('driven.torque', 0.9, 1.0))} N·m", 'mean of `driven.torque` over 0.9–1 s'),
    ])
    # the probe's passages: the first lower span lies between its first driven and first driver contacts
    drv0, drn0 = d.on('driver')[0], d.on('driven')[0]
    lower0 = (drn0['t1'], drv0['t0'])
    upper0 = (drv0['t1'], d.on('driven', after=drv0['t1'])[0]['t0'])
    def mid_mean(t0, t1):  # the middle half of a passage: away from the pulleys
        q = (t1 - t0) / 4
        return d.mean('probe.sde_force', t0 + q, t1 - q)
    last_drv = d.on('driver')[-1]
    last_lower = (max(c['t1'] for c in d.on('driven') if c['t1'] < last_drv['t0']), last_drv['t0'])
    peak_t, peak = d.extreme('probe.sde_force', 0.25, 1.0)
    out['10'] = table([
        ('first passage on the lower (tight) span', '"within the time range of up to 0.25 s" (Fig. 10, §3)',
         f'{ms(lower0[0])}–{ms(lower0[1])} s', 'between the end of the probe\'s first contact (driven pulley) '
         'and the start of its second (driver), from `probe.normal_force` > 0'),
        ('SDE force there, largest', '"maximum value … about 820 N" (Fig. 10, §3)',
         f"{num(d.extreme('probe.sde_force', *lower0)[1])} N", 'largest `probe.sde_force` in that passage'),
        ('lower span in steady running', '≈ 820 N (Fig. 10)',
         f"{num(mid_mean(*last_lower))} N (span: {num(d.mean('span_driven_driver.tension', 0.9, 1.0))} N)",
         f'mean of `probe.sde_force` over the middle half of the last lower-span passage '
         f'({ms(last_lower[0])}–{ms(last_lower[1])} s); span: mean of `span_driven_driver.tension` over 0.9–1 s'),
        ('first passage on the upper (slack) span', '"about 0.35 s to about 0.4 s" (Fig. 10, §3)',
         f'{ms(upper0[0])}–{ms(upper0[1])} s', 'between the probe\'s first driver contact and its next driven contact'),
        ('SDE force there', '"about 210 N" (Fig. 10, §3)',
         f"{num(mid_mean(*upper0))} N (span: {num(d.mean('span_driver_driven.tension', 0.9, 1.0))} N)",
         'mean of `probe.sde_force` over the middle half of that passage; span: mean of '
         '`span_driver_driven.tension` over 0.9–1 s'),
        ('largest SDE force after the start', 'not stated; the largest value the text gives is 820 N',
         f'{num(peak)} N at {ms(peak_t)} s, on the {d.where(peak_t)}',
         'largest `probe.sde_force` over 0.25–1 s'),
    ])
    def thirds(ct):
        n = d.samples(ct, 'probe.normal_force')
        k = max(1, len(n) // 3)
        return sum(n[:k]) / k, sum(n[-k:]) / k
    drn, drv = d.on('driven', after=0.3)[-1], d.on('driver', after=0.3)[-1]
    (dn_a, dn_b), (dv_a, dv_b) = thirds(drn), thirds(drv)
    entry_t, entry = d.extreme('probe.normal_force', drv['t0'], drv['t1'])
    out['11'] = table([
        ('order of contacts', '"first … the driven pulley … then … the driving pulley" (Figs 11–12, §3)',
         ', '.join(f"{c['pulley']} {interval(c)}" for c in d.contacts[:4]) + ', …',
         'intervals of `probe.normal_force` > 0, given to the pulleys in the route\'s order'),
        ('N along the driven pulley', '"gradually increases" (from the slack to the tight side; §3)',
         f'{num(dn_a)} N → {num(dn_b)} N', f'mean `probe.normal_force` over the first and the last third of the '
         f'last complete driven contact ({interval(drn)})'),
        ('N along the driving pulley', '"gradually decreases" (from the tight to the slack side; §3)',
         f'{num(dv_a)} N → {num(dv_b)} N', f'the same over the last complete driver contact ({interval(drv)})'),
        ('N where the belt meets the driver', 'not stated', f'{num(entry)} N at {ms(entry_t)} s',
         'largest `probe.normal_force` in that driver contact'),
    ])
    dry_contact = [(abs(f), n) for ti, f, n in zip(d.t, d.col('probe.friction_force'), d.col('probe.normal_force'))
                   if ti >= 0.3 and n > 0 and f == f]
    saturated = sum(1 for f, n in dry_contact if f >= 0.98 * n) / len(dry_contact)
    ratio = sum(f for f, _ in dry_contact) / sum(n for _, n in dry_contact)
    out['12'] = table([
        ('|T| against N (μ = 1)', '"courses shown in Fig. 11 and 12 are very similar" (§3)',
         f'Σ|T| / ΣN = {num(ratio, 2)}', 'over every contact sample from 0.3 s on'),
        ('fully developed friction, |T| = μN', '"predominantly … maximum (fully developed) static friction or '
         'kinetic friction" (§3)', f'{100 * saturated:.0f} % of the contact time',
         'share of the contact samples from 0.3 s on with |`probe.friction_force`| ≥ 0.98·`probe.normal_force`'),
        ('sign of T', 'a value (the figure\'s sign convention is not given)',
         'driver > 0, driven < 0', 'the friction pulls the belt forward on the driver and holds it back on the '
         'driven pulley (checked for every contact after the first lap)'),
    ])
    slip = [abs(s) for ti, s in zip(d.t, d.col('probe.slip_velocity')) if ti >= 0.3 and s == s]
    slipping = sum(1 for s in slip if s > DV) / len(slip)
    slip_sorted = sorted(slip)
    out['13'] = table([
        ('the element slips', '"analysed belt element slips on the pulleys" (Fig. 13, §3)',
         f'{100 * slipping:.0f} % of the contact time', 'share of the contact samples from 0.3 s on with '
         f'|`probe.slip_velocity`| > Δv = {DV_TEXT}'),
        ('… but slowly', '"the slip velocity is relatively small" (Fig. 13, §3)',
         f'median {num(slip_sorted[len(slip) // 2], 2)} m/s, largest {num(slip_sorted[-1], 2)} m/s',
         f'|`probe.slip_velocity`| over the contact samples from 0.3 s on; the belt runs at '
         f"{num(abs(w2) * float(d.p['pulley.driven.radius']))} m/s"),
    ])
    return out


def wet_figures(w, d):
    out = {}
    w2max_t, w2max = w.extreme('driven.omega', 0.0, 1.0)
    lo = min(y for _, y in w.window('driven.omega', 0.5, 1.0))
    hi = max(y for _, y in w.window('driven.omega', 0.5, 1.0))
    depart = next(ti for ti, a, b in zip(w.t, w.col('driver.omega'), d.col('driver.omega')) if abs(a - b) > 1.0)
    out['15'] = table([
        ('driving pulley at the end', '"over 600 rad/s" (Fig. 15, §3)', f"{num(w.at('driver.omega', 1.0))} rad/s",
         '`driver.omega` at t = 1 s'),
        ('driving pulley on the way', 'not stated', ', '.join(f"{num(w.at('driver.omega', x))} rad/s at {x} s"
                                                              for x in (0.3, 0.6)), '`driver.omega` at those times'),
        ('driver leaves the dry run\'s curve', 'not stated (the wet half reaches the driver; Fig. 14)',
         f'{ms(depart)} s', 'first t with |`driver.omega` − the dry run\'s| > 1 rad/s'),
        ('driven pulley, largest speed', '"not exceeding 70 rad/s" (Fig. 15, §3)',
         f'{num(w2max)} rad/s at {ms(w2max_t)} s', 'largest |`driven.omega`| over 0–1 s'),
        ('driven pulley oscillates', '"oscillating values … successive changes of dry and wet parts" (§3)',
         f'between {num(hi)} and {num(lo)} rad/s', 'range of `driven.omega` over 0.5–1 s'),
    ])
    tmax_t, tmax = w.extreme('driven.torque', 0.0, 1.0)
    out['16'] = table([
        ('resistance torque ≠ driving torque', '"resistance torque also not equals the driving torque" (Fig. 16, §3)',
         f"mean {num(w.mean('driven.torque', 0.5, 1.0))} N·m against {num(w.mean('driver.torque', 0.5, 1.0))} N·m",
         'means of `driven.torque` and `driver.torque` over 0.5–1 s'),
        ('largest resistance torque', '"the maximum values also reaches 65 Nm" (Fig. 16, §3)',
         f'{num(tmax)} N·m at {ms(tmax_t)} s', 'largest `driven.torque` over 0–1 s'),
        ('oscillating', '"oscillating values of resistance torque" (§3)',
         f"{num(min(y for _, y in w.window('driven.torque', 0.5, 1.0)))}–"
         f"{num(max(y for _, y in w.window('driven.torque', 0.5, 1.0)))} N·m", 'range of `driven.torque` over 0.5–1 s'),
    ])
    def contact_abs(run, pulley=None):
        f, n = [], []
        for ct in run.contacts:
            if ct['t0'] >= 0.3 and (pulley is None or ct['pulley'] == pulley):
                f += [abs(x) for x in run.samples(ct, 'probe.friction_force')]
                n += run.samples(ct, 'probe.normal_force')
        return f, n
    fw, nw = contact_abs(w)
    fd, _ = contact_abs(d)
    out['17'] = table([
        ('friction force of the wet element', '"about 20% of values calculated in case of dry belt" (Fig. 17 '
         'against Fig. 12, §3)', f'{100 * (sum(fw) / len(fw)) / (sum(fd) / len(fd)):.0f} % (mean |T|), '
         f'{100 * max(fw) / max(fd):.0f} % (largest |T|)',
         'mean and largest |`probe.friction_force`| over the contact samples from 0.3 s on, half-wet run over dry run'),
        ('proportional to μ = 0.2', '"changed proportionally to assumed lower value of friction coefficient" (§3)',
         f'Σ|T| / ΣN = {num(sum(fw) / sum(nw), 2)}', 'over the wet element\'s contact samples from 0.3 s on'),
    ])
    slip = [s for ti, s in zip(w.t, w.col('probe.slip_velocity')) if ti >= 0.3 and s == s]
    slipping = sum(1 for s in slip if abs(s) > DV) / len(slip)
    def durations(pulley):
        cs = w.on(pulley, after=0.4)
        return sum(c['t1'] - c['t0'] for c in cs) / len(cs), sum(w.belt_speed(c) for c in cs) / len(cs), len(cs)
    (dd, vd, nd), (dn, vn, nn) = durations('driver'), durations('driven')
    out['18'] = table([
        ('the element slips', '"Except starting phase, the velocity is greater than zero" (Fig. 18, §3)',
         f'{100 * slipping:.0f} % of the contact time', 'share of the contact samples from 0.3 s on with '
         f'|`probe.slip_velocity`| > Δv (the sign: < 0 on the driver, whose rim outruns the belt; > 0 on the '
         'driven pulley)'),
        ('contact with the driven pulley is shorter', '"much shorter time intervals of contact with driven pulley '
         'than with drive pulley" (§3)', f'driven {1000 * dn:.0f} ms, driver {1000 * dd:.0f} ms',
         f'mean length of the probe\'s contacts from 0.4 s on ({nn} driven, {nd} driver)'),
        ('… and why', '"because of acting centrifugal force and bending stiffness, with increasing belt velocity" '
         '(§3)', f'the element runs at {num(vn)} m/s over the driven pulley, {num(vd)} m/s over the driver',
         'mean of `probe.slip_velocity` + the rim speed |ω|·r of the pulley touched, over those contacts'),
    ])
    return out


def automotive_figures(a):
    out = {}
    early = {p: a.mean(p + '.omega', 0.05, 0.2) for p in ('crankshaft', 'alternator', 'pump', 'tensioner')}
    alt_t, alt = a.extreme('alternator.omega', 0.1, 0.3)
    ten_t, ten = a.extreme('tensioner.omega', 0.1, 0.3)
    out['20'] = table([
        ('directions', 'crankshaft, alternator, pump negative (clockwise); tensioner positive (Fig. 20, §4)',
         ', '.join(f'{p} {num(v)}' for p, v in early.items()) + ' rad/s; tensioner ≥ '
         f"{num(min(y for _, y in a.window('tensioner.omega', 0.01, 1.0)))} rad/s throughout",
         'means of `<pulley>.omega` over 0.05–0.2 s; smallest `tensioner.omega` over 0.01–1 s'),
        ('the other pulleys stop speeding up', '"just before 0.2 s" (Fig. 20, §4)',
         f'alternator at {ms(alt_t)} s ({num(alt)} rad/s), tensioner at {ms(ten_t)} s ({num(ten)} rad/s)',
         'time of the largest |`alternator.omega`|, |`tensioner.omega`| over 0.1–0.3 s'),
        ('the crankshaft runs away', '"from this moment, crankshaft pulley angular velocity started rapidly '
         'increasing" (§4)', ', '.join(f"{num(a.at('crankshaft.omega', x))} rad/s at {x} s" for x in (0.2, 0.3, 0.5)),
         '`crankshaft.omega` at those times'),
    ])
    jump_i = max((i for i in range(1, len(a.t)) if 0.1 <= a.t[i] <= 0.3),
                 key=lambda i: a.col('pump.torque')[i] - a.col('pump.torque')[i - 1])
    pmax_t, pmax = a.extreme('pump.torque', 0.15, 0.3)
    out['21'] = table([
        ('the pump meets dry belt: its torque jumps', '"to about 0.22 s … the pump contact with wet part … At this '
         'moment, the resistance torque increases rapidly" (Fig. 21, §4)', f'steepest rise at {ms(a.t[jump_i])} s',
         'largest increase of `pump.torque` between samples over 0.1–0.3 s'),
        ('… to', '"about 30 Nm" (Fig. 21, §4)', f'{num(pmax)} N·m at {ms(pmax_t)} s',
         'largest `pump.torque` over 0.15–0.3 s'),
        ('driving torque', '70 N·m from 0.3 s (Fig. 7a, input)', f"{num(a.mean('crankshaft.torque', 0.9, 1.0))} N·m",
         'mean of `crankshaft.torque` over 0.9–1 s'),
        ('alternator, tensioner', '"rest of resistance torques are assumed as negligible" (§4)',
         f"{num(max(abs(y) for _, y in a.window('alternator.torque', 0, 1) + a.window('tensioner.torque', 0, 1)) or 0)} N·m",
         'largest |`alternator.torque`|, |`tensioner.torque`| (no torque law: zero lines)'),
        ('the belt slows', '"the velocity of the transmission (the belt) started decreasing" (§4)',
         f"alternator {num(a.at('alternator.omega', 0.2))} rad/s at 0.2 s, {num(a.at('alternator.omega', 0.3))} rad/s "
         'at 0.3 s', '`alternator.omega` at those times'),
    ])
    pump0 = a.on('pump', complete=False)[0]
    crank0 = a.on('crankshaft')[0]
    def peak_f(cts):
        return sum(max(abs(x) for x in a.samples(c, 'probe.friction_force')) for c in cts) / len(cts)
    out['22'] = table([
        ('contact with the pump', '"from 0.17 s to 0.2 s" (Fig. 22, §4)', interval(pump0),
         '`probe.normal_force` > 0; our probe starts on the pump (the contact runs from t = 0)'),
        ('contact with the crankshaft', '"from 0.26 s" (Fig. 22, §4)', interval(crank0),
         'its next contact (the pump–crankshaft span between)'),
        ('friction larger on the pump (smaller radius)', '"greater values of friction forces acting from the pump '
         'pulley" (§4)', f"pump {num(peak_f(a.on('pump', after=0.4)))} N, crankshaft "
         f"{num(peak_f(a.on('crankshaft', after=0.4)))} N",
         'largest |`probe.friction_force`| per contact, averaged over the contacts from 0.4 s on '
         '(the first ones: pump while the drive starts from rest, crankshaft while the wet element slips)'),
    ])
    smax_t, smax = a.extreme('probe.sde_force', 0.15, 0.35)
    tmax_t, tmax = a.extreme('span_pump_crankshaft.tension', 0.15, 0.35)
    out['23'] = table([
        ('the SDE force rises sharply', '"at the time about 0.22 s" (Fig. 23, §4)', f'largest at {ms(smax_t)} s',
         'time of the largest `probe.sde_force` over 0.15–0.35 s'),
        ('… to', '"about 890 N" (Fig. 23, §4)', f'{num(smax)} N', 'that largest value'),
        ('where the SDE is then', '"between the pump pulley and crankshaft pulley" (§4)',
         f'the probe element is on the {a.where(smax_t)} (its SDE joins it to the element behind, towards the pump)',
         'the probe\'s contacts, as above'),
        ('the pump–crankshaft (tight) span itself', 'not stated', f'{num(tmax)} N at {ms(tmax_t)} s',
         'largest `span_pump_crankshaft.tension` over 0.15–0.35 s'),
    ])
    return out


def main():
    if len(sys.argv) != 3:
        sys.exit(__doc__.split('\n\n')[1])
    runs, page = sys.argv[1], sys.argv[2]
    dry = Run(os.path.join(runs, 'paper_dry'), first_pulley='driven', drive_pulley='driver')
    wet = Run(os.path.join(runs, 'paper_wet'), first_pulley='driven', drive_pulley='driver')
    auto = Run(os.path.join(runs, 'automotive_wet'), first_pulley='pump', drive_pulley='crankshaft')
    tables = {**dry_figures(dry), **wet_figures(wet, dry), **automotive_figures(auto)}
    with open(page, encoding='utf-8') as f:
        text = f.read()
    for n, body in tables.items():
        pattern = re.compile(r'(<!-- paper_values fig%s -->\n).*?(<!-- /paper_values -->)' % n, re.S)
        if not pattern.search(text):
            sys.exit(f'paper_values: {page} has no block <!-- paper_values fig{n} --> … <!-- /paper_values -->')
        text = pattern.sub(lambda m: m.group(1) + body + '\n' + m.group(2), text)
    with open(page, 'w', encoding='utf-8') as f:
        f.write(text)
    for n, body in tables.items():
        print(f'Fig. {n}\n{body}\n')


if __name__ == '__main__':
    main()
