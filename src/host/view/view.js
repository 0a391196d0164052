/*
 * view.js - the xgo-emu view page (docs/view.md): a 3D view of the robot
 * drawn on a canvas from the joint angles, the board's state beside it, and a
 * remote control that writes registers through POST /command.
 *
 * Data: GET meta (register, action, mode, gait names, joint limits, leg
 * geometry, register ranges: all from the core, so nothing here re-types a
 * core table) and the SSE stream `events` (one state JSON per event, contract
 * in docs/view.md). The legs are drawn from joints_deg through the same leg
 * kinematics as the core (xgo_leg_fk, docs/geometry.md) with the geometry from
 * meta; feet_mm (the core's own FK) is the cross-check shown under "State".
 *
 * For the browser test <body> carries data-frames-drawn (canvas frames that
 * showed the robot), data-last-state-ms (board time of the pose last drawn)
 * and data-connected ("1"/"0").
 */
(function () {
  'use strict';

  var RAD = Math.PI / 180;
  var INTERP_DELAY_MS = 70;     /* render this far behind the newest state: 2 events at 30 Hz */
  var STALE_MS = 2500;          /* no event for this long: the link is down */
  var TRAIL_MAX = 4000;         /* points kept (at >= 5 mm apart: 20 m of path) */
  var LOG_MAX = 400;            /* frame log lines kept */
  var LEG_NAMES = ['LF', 'RF', 'RH', 'LH'];
  var JOINT_NAMES = ['knee', 'hip', 'abad'];

  var $ = function (id) { return document.getElementById(id); };
  var body = document.body;

  /* ------------------------------------------------------------ helpers */

  function clamp(v, lo, hi) { return v < lo ? lo : (v > hi ? hi : v); }
  function lerp(a, b, t) { return a + (b - a) * t; }
  function lerpDeg(a, b, t) { /* shortest way round, for headings */
    var d = ((b - a) % 360 + 540) % 360 - 180;
    return a + d * t;
  }
  function fix(v, n) { return (typeof v === 'number' && isFinite(v)) ? v.toFixed(n) : '-'; }
  function hex2(v) { return (v < 16 ? '0' : '') + v.toString(16).toUpperCase(); }

  function postJson(path, obj, statusEl) {
    var req = new XMLHttpRequest();
    req.open('POST', path);
    req.setRequestHeader('Content-Type', 'application/json');
    req.onload = function () {
      statusEl.textContent = req.status === 200 ? 'ok ' + path + ' ' + req.responseText.slice(0, 160)
        : 'HTTP ' + req.status + ': ' + req.responseText.slice(0, 200);
      statusEl.className = 'mono small ' + (req.status === 200 ? 'muted' : 'bad');
    };
    req.onerror = function () { statusEl.textContent = path + ': no answer from xgo-emu'; };
    req.send(JSON.stringify(obj));
  }

  /* ------------------------------------------------------------ meta */

  var meta = null;              /* GET meta, or null before it arrives */
  var regByName = {};           /* "vx" -> descriptor */
  var regNameAt = [];           /* address -> "vx", "bt_name[3]", or "" */

  function loadMeta(done) {
    var req = new XMLHttpRequest();
    req.open('GET', 'meta');
    req.timeout = 3000;         /* a hung server must not stop the reconnecting */
    req.ontimeout = function () { done(false); };
    req.onload = function () {
      if (req.status !== 200) { return done(false); }
      try { applyMeta(JSON.parse(req.responseText)); } catch (e) { return done(false); }
      done(true);
    };
    req.onerror = function () { done(false); };
    req.send();
  }

  function applyMeta(m) {
    meta = m;
    regByName = {};
    regNameAt = [];
    (m.registers || []).forEach(function (r) {
      regByName[r.name] = r;
      for (var i = 0; i < r.width; i++) {
        /* the first name wins: gait_type (0x09) inside the firmware window */
        if (!regNameAt[r.addr + i]) { regNameAt[r.addr + i] = r.width > 1 ? r.name + '[' + i + ']' : r.name; }
      }
    });
    $('model').textContent = m.model || '-';
    buildRegmap();
    buildJoints();
    buildControls();
  }

  /* ------------------------------------------------------------ link */

  var source = null;
  var lastEventAt = 0;
  var retryTimer = null;
  var attempts = 0;

  function setConnected(up) {
    body.dataset.connected = up ? '1' : '0';
    $('link').className = 'link ' + (up ? 'up' : 'down');
    $('link').textContent = up ? 'connected' : (attempts > 0 ? 'connection lost, retry ' + attempts : 'connecting...');
    $('lost').hidden = up || attempts === 0;
  }

  function connect() {
    if (retryTimer) { clearTimeout(retryTimer); retryTimer = null; }
    if (source) { source.close(); source = null; }
    loadMeta(function () {
      source = new EventSource('events');
      source.onmessage = function (ev) {
        var s;
        try { s = JSON.parse(ev.data); } catch (e) { return; }
        lastEventAt = performance.now();
        if (body.dataset.connected !== '1') { attempts = 0; setConnected(true); }
        onState(s);
      };
      source.onerror = function () { linkLost(); };
    });
  }

  /* EventSource retries by itself only while the server answers; after a
   * refused connection it stays closed. Retry ourselves, at most every 2 s. */
  function linkLost() {
    if (source) { source.close(); source = null; }
    attempts++;
    setConnected(false);
    if (!retryTimer) { retryTimer = setTimeout(connect, Math.min(500 * attempts, 2000)); }
  }

  setInterval(function () {
    if (body.dataset.connected === '1' && performance.now() - lastEventAt > STALE_MS) { linkLost(); }
  }, 500);

  /* ------------------------------------------------------------ states */

  var states = [];              /* recent states, oldest first, for interpolation */
  var offsets = [];             /* local arrival time - t_ms of recent states */
  var latest = null;
  var trail = [];               /* {x, y} world points, mm */

  function onState(s) {
    var now = performance.now();
    if (latest && s.t_ms < latest.t_ms) { /* board time went back: xgo-emu restarted */
      states = []; offsets = []; trail = [];
    }
    latest = s;
    states.push(s);
    if (states.length > 40) { states.shift(); }
    offsets.push(now - s.t_ms);
    if (offsets.length > 60) { offsets.shift(); }
    addTrail(s.world);
    updatePanels(s);
  }

  function addTrail(w) {
    var last = trail[trail.length - 1];
    if (!w) { return; }
    if (!last || Math.hypot(w.x_mm - last.x, w.y_mm - last.y) >= 5) {
      trail.push({ x: w.x_mm, y: w.y_mm });
      if (trail.length > TRAIL_MAX) { trail.shift(); }
    }
  }

  /* Board time to draw now: the newest state's clock mapped to ours by the
   * smallest arrival delay seen (the least delayed event), minus a margin so
   * there is usually a state on each side to interpolate between. */
  function renderTime() {
    var off = Math.min.apply(null, offsets);
    return performance.now() - off - INTERP_DELAY_MS;
  }

  function pose(a) {
    return { j: a.joints_deg, body: a.body, world: a.world, contacts: a.contacts, arm: a.arm || null,
             t: a.t_ms };
  }

  function mixPose(a, b, t) {
    var j = [], k;
    for (k = 0; k < 12; k++) { j.push(lerp(a.joints_deg[k], b.joints_deg[k], t)); }
    return {
      j: j,
      body: {
        x_mm: lerp(a.body.x_mm, b.body.x_mm, t), y_mm: lerp(a.body.y_mm, b.body.y_mm, t),
        z_mm: lerp(a.body.z_mm, b.body.z_mm, t), roll_deg: lerp(a.body.roll_deg, b.body.roll_deg, t),
        pitch_deg: lerp(a.body.pitch_deg, b.body.pitch_deg, t), yaw_deg: lerpDeg(a.body.yaw_deg, b.body.yaw_deg, t)
      },
      world: { x_mm: lerp(a.world.x_mm, b.world.x_mm, t), y_mm: lerp(a.world.y_mm, b.world.y_mm, t),
               yaw_deg: lerpDeg(a.world.yaw_deg, b.world.yaw_deg, t) },
      contacts: t < 0.5 ? a.contacts : b.contacts,
      arm: mixArm(a.arm, b.arm, t),
      t: lerp(a.t_ms, b.t_ms, t)
    };
  }

  /* The Mini2's arm between two states ("arm" is null without one). */
  function mixArm(a, b, t) {
    if (!a || !b) { return t < 0.5 ? (a || null) : (b || null); }
    function mix3(p, q) { return [lerp(p[0], q[0], t), lerp(p[1], q[1], t), lerp(p[2], q[2], t)]; }
    return { joints_deg: [0, 1, 2].map(function (k) { return lerp(a.joints_deg[k], b.joints_deg[k], t); }),
             shoulder_mm: mix3(a.shoulder_mm, b.shoulder_mm), elbow_mm: mix3(a.elbow_mm, b.elbow_mm),
             claw_mm: mix3(a.claw_mm, b.claw_mm), out_of_reach: b.out_of_reach };
  }

  function currentPose() {
    var rt, i, a, b;
    if (!states.length) { return null; }
    rt = renderTime();
    if (rt <= states[0].t_ms) { return pose(states[0]); }
    for (i = states.length - 1; i > 0; i--) {
      a = states[i - 1]; b = states[i];
      if (rt >= a.t_ms && rt < b.t_ms) { return mixPose(a, b, (rt - a.t_ms) / (b.t_ms - a.t_ms)); }
    }
    return pose(states[states.length - 1]);
  }

  /* ------------------------------------------------------------ kinematics */

  /* The leg as four points in the body frame (mm, z up): abduction axis,
   * thigh joint, knee, foot. Same model and signs as xgo_leg_fk: q = [x1
   * knee, x2 hip, x3 abad] in degrees, leg 0 LF, 1 RF, 2 RH, 3 LH. */
  function legPoints(g, leg, q) {
    var sx = leg < 2 ? 1 : -1, sy = (leg === 0 || leg === 3) ? 1 : -1;
    var d = g.abad_offset_mm, l1 = g.thigh_mm, l2 = g.shank_mm;
    var t2 = q[1] * RAD, phi = q[2] * RAD, gk = (q[0] + g.knee_offset_deg) * RAD;
    var ox = sx * g.hip_x_mm, oy = sy * (g.hip_y_mm + d);
    var cp = Math.cos(phi), sp = Math.sin(phi);
    function plane(x, h) { /* leg-plane point (x ahead, h below the thigh joint) */
      var out = d * cp + h * sp, down = -d * sp + h * cp;
      return [ox + x, oy + sy * (out - d), -down];
    }
    var kx = -l1 * Math.sin(t2), kh = l1 * Math.cos(t2);
    return [[ox, sy * g.hip_y_mm, 0], plane(0, 0), plane(kx, kh),
            plane(kx + l2 * Math.cos(t2 + gk), kh + l2 * Math.sin(t2 + gk))];
  }

  /* Largest distance between our FK foot and the core's feet_mm. */
  function fkCheck(s) {
    var worst = 0, leg, p, f;
    if (!meta || !meta.geometry || !s.feet_mm) { return null; }
    for (leg = 0; leg < 4; leg++) {
      p = legPoints(meta.geometry, leg, s.joints_deg.slice(3 * leg, 3 * leg + 3))[3];
      f = s.feet_mm[leg];
      worst = Math.max(worst, Math.hypot(p[0] - f[0], p[1] - f[1], p[2] - f[2]));
    }
    return worst;
  }

  /* Body frame -> world: body pose in the machine frame (R = Rz Ry Rx about
   * the body centre, then the translation), then the world pose. */
  function bodyToWorld(p) {
    var b = p.body, w = p.world;
    var cr = Math.cos(b.roll_deg * RAD), sr = Math.sin(b.roll_deg * RAD);
    var cpi = Math.cos(b.pitch_deg * RAD), spi = Math.sin(b.pitch_deg * RAD);
    var cy = Math.cos(b.yaw_deg * RAD), sy = Math.sin(b.yaw_deg * RAD);
    var cw = Math.cos(w.yaw_deg * RAD), sw = Math.sin(w.yaw_deg * RAD);
    var m = [[cy * cpi, cy * spi * sr - sy * cr, cy * spi * cr + sy * sr],
             [sy * cpi, sy * spi * sr + cy * cr, sy * spi * cr - cy * sr],
             [-spi, cpi * sr, cpi * cr]];
    return function (v) {
      var mx = m[0][0] * v[0] + m[0][1] * v[1] + m[0][2] * v[2] + b.x_mm;
      var my = m[1][0] * v[0] + m[1][1] * v[1] + m[1][2] * v[2] + b.y_mm;
      var mz = m[2][0] * v[0] + m[2][1] * v[1] + m[2][2] * v[2] + b.z_mm;
      return [w.x_mm + cw * mx - sw * my, w.y_mm + sw * mx + cw * my, mz];
    };
  }

  /* ------------------------------------------------------------ camera */

  var canvas = $('scene');
  var ctx = canvas.getContext('2d');
  var cam = { az: 0.75, el: 0.42, dist: 700, target: [0, 0, 60], pan: [0, 0, 0] };
  var view = null;              /* this frame's projection */

  function homeView() {
    cam.az = 0.75; cam.el = 0.42; cam.dist = 700; cam.pan = [0, 0, 0];
  }

  function setupView(w, h) {
    var ce = Math.cos(cam.el), t = cam.target;
    var eye = [t[0] + cam.dist * ce * Math.cos(cam.az), t[1] + cam.dist * ce * Math.sin(cam.az),
               t[2] + cam.dist * Math.sin(cam.el)];
    var f = norm([t[0] - eye[0], t[1] - eye[1], t[2] - eye[2]]);
    var r = norm(cross(f, [0, 0, 1]));
    view = { eye: eye, f: f, r: r, u: cross(r, f), cx: w / 2, cy: h / 2,
             focal: h / (2 * Math.tan(25 * RAD)), near: 10 };
  }

  function norm(v) { var n = Math.hypot(v[0], v[1], v[2]) || 1; return [v[0] / n, v[1] / n, v[2] / n]; }
  function cross(a, b) { return [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]]; }
  function dot(a, b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }

  function toCam(p) {
    var d = [p[0] - view.eye[0], p[1] - view.eye[1], p[2] - view.eye[2]];
    return [dot(d, view.r), dot(d, view.u), dot(d, view.f)];
  }

  function project(c) { /* camera coordinates -> [sx, sy, depth] */
    return [view.cx + view.focal * c[0] / c[2], view.cy - view.focal * c[1] / c[2], c[2]];
  }

  /* World segment -> screen segment clipped at the near plane, or null. */
  function segment(a, b) {
    var ca = toCam(a), cb = toCam(b), t;
    if (ca[2] < view.near && cb[2] < view.near) { return null; }
    if (ca[2] < view.near || cb[2] < view.near) {
      t = (view.near - ca[2]) / (cb[2] - ca[2]);
      var cut = [lerp(ca[0], cb[0], t), lerp(ca[1], cb[1], t), view.near];
      if (ca[2] < view.near) { ca = cut; } else { cb = cut; }
    }
    return [project(ca), project(cb)];
  }

  function point(p) {
    var c = toCam(p);
    return c[2] < view.near ? null : project(c);
  }

  /* ------------------------------------------------------------ drawing */

  function resizeCanvas() {
    var dpr = window.devicePixelRatio || 1, w = canvas.clientWidth, h = canvas.clientHeight;
    if (canvas.width !== Math.round(w * dpr) || canvas.height !== Math.round(h * dpr)) {
      canvas.width = Math.round(w * dpr); canvas.height = Math.round(h * dpr);
    }
    ctx.setTransform(dpr, 0, 0, dpr, 0, 0);
    return [w, h];
  }

  function drawGrid() {
    var step = 100, span = 2000, t = cam.target, x, y, i;
    var x0 = Math.floor((t[0] - span) / step) * step, y0 = Math.floor((t[1] - span) / step) * step;
    ctx.lineWidth = 1;
    for (i = 0; i <= 2 * span / step; i++) {
      x = x0 + i * step; y = y0 + i * step;
      gridLine([x, y0, 0], [x, y0 + 2 * span, 0], x === 0 ? '#a04040' : (x % 500 === 0 ? '#3d4656' : '#2a303b'));
      gridLine([x0, y, 0], [x0 + 2 * span, y, 0], y === 0 ? '#40a050' : (y % 500 === 0 ? '#3d4656' : '#2a303b'));
    }
  }

  function gridLine(a, b, color) {
    var s = segment(a, b);
    if (!s) { return; }
    ctx.strokeStyle = color;
    ctx.beginPath(); ctx.moveTo(s[0][0], s[0][1]); ctx.lineTo(s[1][0], s[1][1]); ctx.stroke();
  }

  /* The path walked: older parts fade out (alpha by position in the trail). */
  function drawTrail() {
    var n = trail.length, groups = 16, g, i, s, from, to;
    if (n < 2 || !$('trail-on').checked) { return; }
    ctx.lineWidth = 2; ctx.lineCap = 'round';
    for (g = 0; g < groups; g++) {
      from = Math.floor(g * (n - 1) / groups); to = Math.floor((g + 1) * (n - 1) / groups);
      ctx.strokeStyle = 'rgba(79,179,255,' + (0.08 + 0.8 * (g + 1) / groups).toFixed(3) + ')';
      ctx.beginPath();
      for (i = from; i < to; i++) {
        s = segment([trail[i].x, trail[i].y, 0.5], [trail[i + 1].x, trail[i + 1].y, 0.5]);
        if (s) { ctx.moveTo(s[0][0], s[0][1]); ctx.lineTo(s[1][0], s[1][1]); }
      }
      ctx.stroke();
    }
  }

  /* Body outline in the body frame, from the hip spacing in meta. */
  function bodyBox(g) {
    var hx = g.hip_x_mm + 32, hy = g.hip_y_mm + 0.4 * g.abad_offset_mm, zb = -16, zt = 22;
    return [[hx, hy, zb], [hx, -hy, zb], [-hx, -hy, zb], [-hx, hy, zb],
            [hx, hy, zt], [hx, -hy, zt], [-hx, -hy, zt], [-hx, hy, zt]];
  }
  var BOX_FACES = [[0, 1, 5, 4, 'front'], [2, 3, 7, 6, 'back'], [3, 0, 4, 7, 'side'],
                   [1, 2, 6, 5, 'side'], [4, 5, 6, 7, 'top'], [3, 2, 1, 0, 'bottom']];

  function drawShadow(corners, legs) {
    var hull = [0, 1, 2, 3].map(function (i) { return point([corners[i][0], corners[i][1], 0]); });
    ctx.fillStyle = 'rgba(0,0,0,0.35)'; ctx.strokeStyle = 'rgba(0,0,0,0.35)';
    if (hull.every(Boolean)) {
      ctx.beginPath(); ctx.moveTo(hull[0][0], hull[0][1]);
      hull.slice(1).forEach(function (p) { ctx.lineTo(p[0], p[1]); });
      ctx.closePath(); ctx.fill();
    }
    legs.forEach(function (pts) {
      var i, s;
      for (i = 0; i < 3; i++) {
        s = segment([pts[i][0], pts[i][1], 0], [pts[i + 1][0], pts[i + 1][1], 0]);
        if (s) {
          ctx.lineWidth = Math.max(1, 9 * view.focal / s[0][2]); ctx.lineCap = 'round';
          ctx.beginPath(); ctx.moveTo(s[0][0], s[0][1]); ctx.lineTo(s[1][0], s[1][1]); ctx.stroke();
        }
      }
    });
  }

  var LIGHT = norm([0.35, 0.25, 0.9]);

  function faceItems(corners, items) {
    BOX_FACES.forEach(function (f) {
      var p = f.slice(0, 4).map(function (i) { return corners[i]; });
      var n = norm(cross(sub(p[3], p[0]), sub(p[1], p[0]))); /* outward */
      var c = [0, 1, 2, 3].map(function (i) { return toCam(p[i]); });
      var center = [(p[0][0] + p[2][0]) / 2, (p[0][1] + p[2][1]) / 2, (p[0][2] + p[2][2]) / 2];
      if (dot(n, sub(view.eye, center)) <= 0 || c.some(function (q) { return q[2] < view.near; })) { return; }
      var shade = 0.45 + 0.55 * Math.max(0, dot(n, LIGHT));
      var base = f[4] === 'front' ? [79, 179, 255] : [200, 205, 215];
      items.push({ depth: (c[0][2] + c[1][2] + c[2][2] + c[3][2]) / 4, draw: function () {
        var s = c.map(project);
        ctx.fillStyle = 'rgb(' + base.map(function (v) { return Math.round(v * shade); }).join(',') + ')';
        ctx.strokeStyle = 'rgba(0,0,0,0.5)'; ctx.lineWidth = 1;
        ctx.beginPath(); ctx.moveTo(s[0][0], s[0][1]);
        s.slice(1).forEach(function (q) { ctx.lineTo(q[0], q[1]); });
        ctx.closePath(); ctx.fill(); ctx.stroke();
      } });
    });
  }

  function sub(a, b) { return [a[0] - b[0], a[1] - b[1], a[2] - b[2]]; }

  var SEGMENT_STYLE = [['#7d8796', 10], ['#c9ced8', 9], ['#e8a33d', 7]]; /* abad link, thigh, shank */

  function legItems(pts, contact, items) {
    var i, s;
    for (i = 0; i < 3; i++) {
      s = segment(pts[i], pts[i + 1]);
      if (s) { items.push(capsule(s, SEGMENT_STYLE[i][0], SEGMENT_STYLE[i][1])); }
    }
    for (i = 1; i < 4; i++) {
      s = point(pts[i]);
      if (s) { items.push(ball(s, i === 3 ? (contact ? '#5fd068' : '#ff7a45') : '#2b313b', i === 3 ? 7 : 5.5)); }
    }
  }

  function capsule(s, color, width) {
    return { depth: (s[0][2] + s[1][2]) / 2, draw: function () {
      ctx.strokeStyle = color; ctx.lineCap = 'round';
      ctx.lineWidth = Math.max(1.5, width * view.focal / ((s[0][2] + s[1][2]) / 2));
      ctx.beginPath(); ctx.moveTo(s[0][0], s[0][1]); ctx.lineTo(s[1][0], s[1][1]); ctx.stroke();
    } };
  }

  function ball(s, color, radius) {
    return { depth: s[2] - 1, draw: function () {
      ctx.fillStyle = color;
      ctx.beginPath(); ctx.arc(s[0], s[1], Math.max(2, radius * view.focal / s[2]), 0, 2 * Math.PI); ctx.fill();
    } };
  }

  var ARM_COLOR = '#d05ce3'; /* the forearm: no other part is this colour (the browser test) */

  /* The Mini2's arm (body frame points from /state's "arm"): upper arm,
   * forearm, and two fingers opening with the claw servo (-65 deg open ..
   * +65 deg closed), 18 mm long, in the arm's plane. */
  function armItems(arm, toWorld, items) {
    var sh = arm.shoulder_mm, el = arm.elbow_mm, cl = arm.claw_mm;
    var len = Math.hypot(cl[0] - el[0], cl[2] - el[2]) || 1;
    var u = [(cl[0] - el[0]) / len, 0, (cl[2] - el[2]) / len], n = [-u[2], 0, u[0]];
    var open = (65 - arm.joints_deg[0]) / 130 * 35 * RAD, tips, s;
    tips = [1, -1].map(function (side) {
      return [cl[0] + 18 * (Math.cos(open) * u[0] + side * Math.sin(open) * n[0]), 0,
              cl[2] + 18 * (Math.cos(open) * u[2] + side * Math.sin(open) * n[2])];
    });
    [[sh, el, '#c9ced8', 8], [el, cl, arm.out_of_reach ? '#ff7a45' : ARM_COLOR, 7],
     [cl, tips[0], '#7d8796', 4], [cl, tips[1], '#7d8796', 4]].forEach(function (seg) {
      s = segment(toWorld(seg[0]), toWorld(seg[1]));
      if (s) { items.push(capsule(s, seg[2], seg[3])); }
    });
    [sh, el].forEach(function (p) {
      s = point(toWorld(p));
      if (s) { items.push(ball(s, '#2b313b', 5.5)); }
    });
  }

  /* Painter's order: the legs sit outside the body's sides, so the two legs
   * on the side away from the camera go first, then the body (a convex box,
   * back faces culled), the arm on its back, then the two near legs; depth
   * sorts within a group. */
  function drawRobot(corners, legs, contacts, arm, toWorld) {
    var leftCentre = mid(corners[0], corners[7]), rightCentre = mid(corners[1], corners[6]);
    var leftNear = dist(view.eye, leftCentre) < dist(view.eye, rightCentre);
    var far = [], boxItems = [], armGroup = [], near = [];
    legs.forEach(function (pts, leg) {
      var left = leg === 0 || leg === 3;
      legItems(pts, contacts[leg], left === leftNear ? near : far);
    });
    faceItems(corners, boxItems);
    if (arm) { armItems(arm, toWorld, armGroup); }
    [far, boxItems, armGroup, near].forEach(function (group) {
      group.sort(function (a, b) { return b.depth - a.depth; }).forEach(function (it) { it.draw(); });
    });
  }

  function mid(a, b) { return [(a[0] + b[0]) / 2, (a[1] + b[1]) / 2, (a[2] + b[2]) / 2]; }
  function dist(a, b) { return Math.hypot(a[0] - b[0], a[1] - b[1], a[2] - b[2]); }

  var framesDrawn = 0;
  var lastDrawAt = 0;

  function draw() {
    var size = resizeCanvas(), p = currentPose(), toWorld, legs, corners;
    lastDrawAt = performance.now();
    if (p && $('follow').checked) { cam.target = [p.world.x_mm + cam.pan[0], p.world.y_mm + cam.pan[1], 60 + cam.pan[2]]; }
    setupView(size[0], size[1]);
    ctx.fillStyle = '#14171c'; ctx.fillRect(0, 0, size[0], size[1]);
    drawGrid();
    drawTrail();
    if (!p || !meta || !meta.geometry) {
      ctx.fillStyle = '#8a93a1'; ctx.font = '14px system-ui';
      ctx.fillText(!p ? 'waiting for the first state...' : 'waiting for meta (leg geometry)...', 16, size[1] - 30);
      return;
    }
    toWorld = bodyToWorld(p);
    legs = [0, 1, 2, 3].map(function (leg) {
      return legPoints(meta.geometry, leg, p.j.slice(3 * leg, 3 * leg + 3)).map(toWorld);
    });
    corners = bodyBox(meta.geometry).map(toWorld);
    drawShadow(corners, legs);
    drawRobot(corners, legs, p.contacts || [1, 1, 1, 1], p.arm, toWorld);
    framesDrawn++;
    body.dataset.framesDrawn = String(framesDrawn);
    body.dataset.lastStateMs = String(Math.round(p.t));
  }

  /* 60 frames/s while the tab is visible; a timer keeps drawing (about
   * 8 frames/s) where requestAnimationFrame is throttled, e.g. headless. */
  function animate() { draw(); requestAnimationFrame(animate); }
  setInterval(function () { if (performance.now() - lastDrawAt > 120) { draw(); } }, 125);

  /* ------------------------------------------------------------ orbit, pan, zoom */

  var drag = null;

  function panBy(dx, dy) {
    var k = cam.dist / view.focal;
    var r = [Math.cos(cam.az + Math.PI / 2), Math.sin(cam.az + Math.PI / 2)];
    var fwd = [-Math.cos(cam.az), -Math.sin(cam.az)];
    var mx = (-dx * r[0] + dy * fwd[0]) * k, my = (-dx * r[1] + dy * fwd[1]) * k;
    cam.pan[0] += mx; cam.pan[1] += my;
    if (!$('follow').checked) { cam.target[0] += mx; cam.target[1] += my; }
  }

  function orbitBy(dx, dy) {
    cam.az -= dx * 0.008;
    cam.el = clamp(cam.el + dy * 0.006, 0.05, 1.5);
  }

  function zoomBy(f) { cam.dist = clamp(cam.dist * f, 150, 6000); }

  canvas.addEventListener('contextmenu', function (e) { e.preventDefault(); });
  canvas.addEventListener('mousedown', function (e) {
    drag = { x: e.clientX, y: e.clientY, pan: e.button === 2 || e.shiftKey || e.button === 1 };
    e.preventDefault();
  });
  window.addEventListener('mousemove', function (e) {
    if (!drag || !view) { return; }
    var dx = e.clientX - drag.x, dy = e.clientY - drag.y;
    drag.x = e.clientX; drag.y = e.clientY;
    if (drag.pan) { panBy(dx, dy); } else { orbitBy(dx, dy); }
  });
  window.addEventListener('mouseup', function () { drag = null; });
  canvas.addEventListener('wheel', function (e) {
    zoomBy(Math.exp(clamp(e.deltaY, -200, 200) * 0.0015)); e.preventDefault();
  }, { passive: false });
  canvas.addEventListener('dblclick', homeView);

  var touches = null;           /* last touch positions, for deltas */

  function touchList(e) {
    return Array.prototype.map.call(e.touches, function (t) { return [t.clientX, t.clientY]; });
  }

  canvas.addEventListener('touchstart', function (e) { touches = touchList(e); e.preventDefault(); }, { passive: false });
  canvas.addEventListener('touchend', function (e) { touches = touchList(e); }, { passive: false });
  canvas.addEventListener('touchmove', function (e) {
    var now = touchList(e);
    if (!touches || !view || now.length !== touches.length) { touches = now; return; }
    if (now.length === 1) {
      orbitBy(now[0][0] - touches[0][0], now[0][1] - touches[0][1]);
    } else if (now.length >= 2) {
      var d0 = Math.hypot(touches[0][0] - touches[1][0], touches[0][1] - touches[1][1]);
      var d1 = Math.hypot(now[0][0] - now[1][0], now[0][1] - now[1][1]);
      if (d0 > 0 && d1 > 0) { zoomBy(d0 / d1); }
      panBy((now[0][0] + now[1][0] - touches[0][0] - touches[1][0]) / 2,
            (now[0][1] + now[1][1] - touches[0][1] - touches[1][1]) / 2);
    }
    touches = now;
    e.preventDefault();
  }, { passive: false });

  $('home-view').addEventListener('click', homeView);
  $('clear-trail').addEventListener('click', function () { trail = []; });
  $('follow').addEventListener('change', function () {
    cam.pan = [0, 0, 0];
    if (!$('follow').checked && latest) { cam.target = [latest.world.x_mm, latest.world.y_mm, 60]; }
  });

  /* ------------------------------------------------------------ panels */

  var lastPanelAt = 0;
  var prevRegs = null;

  function updatePanels(s) {
    var now = performance.now();
    updateRegmap(s);
    appendLog(s);
    if (now - lastPanelAt < 100) { return; } /* text at 10 Hz is enough to read */
    lastPanelAt = now;
    $('clock').textContent = 't = ' + fix(s.t_ms / 1000, 2) + ' s';
    updateStatus(s);
    updateJoints(s);
    updateCounters(s);
    syncControls(s);
  }

  function speedText(v) {
    return 'vx ' + fix(v.vx_mm_s, 0) + ', vy ' + fix(v.vy_mm_s, 0) + ' mm/s, yaw ' + fix(v.vyaw_deg_s, 1) + ' deg/s';
  }

  function updateStatus(s) {
    var fk = fkCheck(s);
    $('s-mode').textContent = s.mode + ' ' + (s.mode_name || '');
    $('s-action').textContent = s.action && s.action.id ? s.action.id + ' ' + s.action.name : 'none';
    $('s-host').textContent = s.host_connected ? 'yes' : 'no';
    $('s-cmd').textContent = speedText(s.speed.cmd);
    $('s-act').textContent = speedText(s.speed.actual);
    $('s-imu').textContent = fix(s.imu.roll_deg, 1) + ' / ' + fix(s.imu.pitch_deg, 1) + ' / ' + fix(s.imu.yaw_deg, 1) + ' deg';
    $('s-world').textContent = fix(s.world.x_mm, 0) + ' / ' + fix(s.world.y_mm, 0) + ' mm / ' + fix(s.world.yaw_deg, 1) + ' deg';
    $('s-batt').textContent = s.battery_pct + ' %';
    $('s-batt-bar').value = s.battery_pct;
    $('s-fk').textContent = fk === null ? '-' : 'max ' + fix(fk, 2) + ' mm apart';
    body.dataset.fkErrorMm = fk === null ? '' : fk.toFixed(3);
    document.querySelectorAll('#actions button').forEach(function (b) {
      b.classList.toggle('running', !!s.action && String(s.action.id) === b.dataset.action);
    });
  }

  function buildJoints() {
    var box = $('joints'), leg, j;
    box.textContent = '';
    for (leg = 0; leg < 4; leg++) {
      for (j = 0; j < 3; j++) {
        var name = document.createElement('div'), bar = document.createElement('div'), val = document.createElement('div');
        name.className = 'mono small'; name.textContent = String(10 * (leg + 1) + j + 1);
        name.title = LEG_NAMES[leg] + ' ' + JOINT_NAMES[j];
        bar.className = 'jbar'; bar.innerHTML = '<div class="zero"></div><div class="pos"></div>';
        val.className = 'jval mono small'; val.textContent = '-';
        box.appendChild(name); box.appendChild(bar); box.appendChild(val);
      }
    }
  }

  function updateJoints(s) {
    var bars = document.querySelectorAll('#joints .jbar'), vals = document.querySelectorAll('#joints .jval');
    var limits = s.joint_limits_deg || (meta && meta.joint_limits_deg);
    if (!limits || bars.length !== 12) { return; }
    s.joints_deg.forEach(function (v, k) {
      var lo = limits[k][0], hi = limits[k][1], span = hi - lo;
      var at = clamp((v - lo) / span, 0, 1);
      bars[k].querySelector('.pos').style.left = (100 * at).toFixed(1) + '%';
      bars[k].querySelector('.zero').style.left = (100 * clamp(-lo / span, 0, 1)).toFixed(1) + '%';
      bars[k].classList.toggle('near', at < 0.03 || at > 0.97);
      bars[k].title = 'limits ' + lo + ' .. ' + hi + ' deg';
      vals[k].textContent = fix(v, 1) + '\u00b0';
    });
  }

  function updateCounters(s) {
    var rows = Object.keys(s.counters || {}).map(function (k) {
      var v = s.counters[k];
      return '<tr' + (v && k !== 'frames_ok' ? ' class="nonzero"' : '') + '><th>' + k + '</th><td>' + v + '</td></tr>';
    }).join('');
    if ($('counters').innerHTML !== rows) { $('counters').innerHTML = rows; }
  }

  /* ------------------------------------------------------------ register map */

  var cells = [];

  function buildRegmap() {
    var box = $('regmap'), i, el;
    box.textContent = '';
    cells = [];
    box.appendChild(document.createElement('div'));
    for (i = 0; i < 16; i++) { el = document.createElement('div'); el.className = 'hd'; el.textContent = '_' + i.toString(16).toUpperCase(); box.appendChild(el); }
    for (i = 0; i < 256; i++) {
      if (i % 16 === 0) { el = document.createElement('div'); el.className = 'hd'; el.textContent = hex2(i).charAt(0) + '_'; box.appendChild(el); }
      el = document.createElement('div');
      el.className = 'cell ' + (regNameAt[i] ? 'named' : 'unmapped');
      el.textContent = '--';
      el.dataset.addr = i;
      box.appendChild(el);
      cells.push(el);
    }
    prevRegs = null;
  }

  $('regmap').addEventListener('mouseover', function (e) {
    var a = e.target.dataset ? e.target.dataset.addr : undefined, v;
    if (a === undefined) { return; }
    v = parseInt(e.target.textContent, 16);
    $('reg-hover').textContent = '0x' + hex2(+a) + ' ' + (regNameAt[a] || '(not on this model)') +
      (isNaN(v) ? '' : ' = 0x' + hex2(v) + ' = ' + v);
  });

  function flash(i) {
    if (cells[i] && cells[i].animate) {
      cells[i].animate([{ background: '#ffd84a', color: '#000' }, { background: 'transparent' }], { duration: 700 });
    }
  }

  function updateRegmap(s) {
    var i, v;
    if (!s.regs || s.regs.length !== 512 || cells.length !== 256) { return; }
    for (i = 0; i < 256; i++) {
      v = s.regs.substr(2 * i, 2).toUpperCase();
      if (!prevRegs || prevRegs.substr(2 * i, 2).toUpperCase() !== v) {
        cells[i].textContent = v;
        if (prevRegs) { flash(i); }
      }
    }
    prevRegs = s.regs;
    (s.frames || []).forEach(function (f) { /* a write flashes its cells even when the value stays */
      if (f.kind === 'rx' && /^write/.test(f.text || '') && f.addr !== undefined) {
        for (i = f.addr; i < f.addr + (f.n || 1) && i < 256; i++) { flash(i); }
      }
    });
  }

  /* ------------------------------------------------------------ frame log */

  function appendLog(s) {
    var log = $('log'), frag, atEnd;
    if (s.frames_omitted) { $('log-omitted').textContent = '(' + s.frames_omitted + ' frames not shown)'; }
    if (!s.frames || !s.frames.length || $('log-pause').checked) { return; }
    atEnd = log.scrollTop + log.clientHeight >= log.scrollHeight - 4;
    frag = document.createDocumentFragment();
    s.frames.forEach(function (f) {
      var line = document.createElement('div');
      line.className = f.kind + (f.source && f.source !== 'wire' ? ' view' : '');
      line.textContent = fix(f.t_ms / 1000, 3).padStart(9) + ' ' + (f.source || '').padEnd(4) + ' ' + f.kind + ' ' + f.text;
      frag.appendChild(line);
    });
    log.appendChild(frag);
    while (log.childNodes.length > LOG_MAX) { log.removeChild(log.firstChild); }
    if (atEnd) { log.scrollTop = log.scrollHeight; }
  }

  $('log-clear').addEventListener('click', function () { $('log').textContent = ''; });

  /* ------------------------------------------------------------ remote control */

  var cmdStatus = $('cmd-status');

  function writeRegs(list) { /* [[name, byte], ...] through POST /command */
    postJson('command', { writes: list.map(function (w) { return { addr: w[0], data: [w[1]] }; }) }, cmdStatus);
  }

  /* Value -> register byte as the vendor library encodes it, over [lo, hi]. */
  function toByte(v, lo, hi) { return clamp(Math.floor(255 * (v - lo) / (hi - lo)), 0, 255); }
  function fromByte(b, lo, hi) { return lo + b * (hi - lo) / 255; }
  /* Centred registers: 0x7F and 0x80 both mean zero, the board's dead band. */
  function fromCentred(b, lo, hi) { return (b === 0x7f || b === 0x80) ? 0 : fromByte(b, lo, hi); }

  var BODY_SLIDERS = [ /* register, label, index into meta.ranges body_mm/body_deg, unit */
    ['body_z', 'height', 'body_mm', 2, 'mm'], ['body_x', 'shift x', 'body_mm', 0, 'mm'],
    ['body_y', 'shift y', 'body_mm', 1, 'mm'], ['body_roll', 'roll', 'body_deg', 0, 'deg'],
    ['body_pitch', 'pitch', 'body_deg', 1, 'deg'], ['body_yaw', 'yaw', 'body_deg', 2, 'deg']];
  var sliders = [];

  function buildControls() {
    buildSelect($('gait'), meta.gaits || []);
    buildSelect($('pace'), meta.paces || []);
    buildBodySliders();
    buildActions();
  }

  function buildSelect(sel, names) {
    sel.textContent = '';
    names.forEach(function (n, i) {
      var o = document.createElement('option'); o.value = i; o.textContent = i + ' ' + n; sel.appendChild(o);
    });
  }

  function buildBodySliders() {
    var box = $('body-sliders'), ranges = meta.ranges || {};
    box.textContent = '';
    sliders = [];
    BODY_SLIDERS.forEach(function (d) {
      var r = ranges[d[2]] && ranges[d[2]][d[3]];
      if (!r || !regByName[d[0]]) { return; }
      var label = document.createElement('label'), input = document.createElement('input'), out = document.createElement('output');
      input.type = 'range'; input.min = 0; input.max = 255; input.step = 1; input.value = 128;
      label.appendChild(document.createTextNode('body ' + d[1]));
      label.appendChild(input); label.appendChild(out);
      box.appendChild(label);
      var sl = { reg: d[0], lo: r[0], hi: r[1], unit: d[4], input: input, out: out, centred: d[0] !== 'body_z', busyUntil: 0 };
      input.addEventListener('input', function () { sl.busyUntil = performance.now() + 1500; showSlider(sl); sendSlider(sl); });
      showSlider(sl);
      sliders.push(sl);
    });
  }

  function showSlider(sl) {
    var b = +sl.input.value;
    var v = sl.centred ? fromCentred(b, sl.lo, sl.hi) : fromByte(b, sl.lo, sl.hi);
    sl.out.textContent = fix(v, 1) + ' ' + sl.unit;
  }

  var sendTimers = {};
  function sendSlider(sl) { /* at most 10 writes/s per slider while dragging */
    if (sendTimers[sl.reg]) { return; }
    sendTimers[sl.reg] = setTimeout(function () { sendTimers[sl.reg] = null; writeRegs([[sl.reg, +sl.input.value]]); }, 100);
  }

  function regByte(s, name) {
    var r = regByName[name];
    return r && s.regs ? parseInt(s.regs.substr(2 * r.addr, 2), 16) : NaN;
  }

  /* Show what the board has (a host on the pty may write too: last write
   * wins), except for a control the user is moving. */
  function syncControls(s) {
    var now = performance.now();
    sliders.forEach(function (sl) {
      var b = regByte(s, sl.reg);
      if (now > sl.busyUntil && !isNaN(b) && +sl.input.value !== b) { sl.input.value = b; showSlider(sl); }
    });
    [['gait', 'gait_type'], ['pace', 'move_mode']].forEach(function (p) {
      var b = regByte(s, p[1]);
      if (document.activeElement !== $(p[0]) && !isNaN(b) && $(p[0]).value !== String(b)) { $(p[0]).value = b; }
    });
    var imu = regByte(s, 'imu_mode');
    if (!isNaN(imu)) { $('stab').checked = imu === 1; }
    if (s.inputs) {
      syncInput('in-roll', s.inputs.ground_roll_deg, ' deg', 1);
      syncInput('in-pitch', s.inputs.ground_pitch_deg, ' deg', 1);
    }
    syncInput('in-batt', s.battery_pct, ' %', 0);
  }

  var inputBusyUntil = {};      /* id -> time until which the user owns it */

  function syncInput(id, v, unit, digits) {
    if (typeof v !== 'number' || performance.now() < (inputBusyUntil[id] || 0)) { return; }
    $(id).value = v;
    $(id + '-v').textContent = fix(v, digits) + unit;
  }

  function buildActions() {
    var box = $('actions');
    box.textContent = '';
    (meta.actions || []).forEach(function (a) {
      if (a.id === 255) { return; } /* the reset button */
      var b = document.createElement('button');
      b.type = 'button'; b.textContent = a.name; b.dataset.action = a.id; b.title = 'action ' + a.id;
      b.addEventListener('click', function () { writeRegs([['action', a.id]]); });
      box.appendChild(b);
    });
  }

  $('gait').addEventListener('change', function () { writeRegs([['gait_type', +$('gait').value]]); });
  $('pace').addEventListener('change', function () { writeRegs([['move_mode', +$('pace').value]]); });
  $('stab').addEventListener('change', function () { writeRegs([['imu_mode', $('stab').checked ? 1 : 0]]); });
  $('btn-stand').addEventListener('click', function () { joySet(0, 0, 0, true); writeRegs([['stand', 1]]); });
  $('btn-reset').addEventListener('click', function () { joySet(0, 0, 0, true); writeRegs([['action', 255]]); });

  /* ------------------------------------------------------------ joystick */

  var joyCanvas = $('joystick'), joyCtx = joyCanvas.getContext('2d');
  var joy = { x: 0, y: 0, side: 0, sent: null, lastSend: 0, timer: null }; /* x right, y up, side = Q/E, in -1..1 */
  var keys = {};

  function joyCommand() { /* stick -> [vx, vy, vyaw] in -1..1 of full scale */
    var k = +$('joy-scale').value / 100, turns = $('joy-x').value === 'turn';
    var vy = turns ? -joy.side : -(joy.x || joy.side);
    return [joy.y * k, clamp(vy, -1, 1) * k, turns ? -joy.x * k : 0];
  }

  function centredByte(f) { return f === 0 ? 0x80 : toByte(f, -1, 1); }

  function joySet(x, y, side, now) {
    joy.x = x; joy.y = y; joy.side = side;
    drawJoystick();
    joySend(now);
  }

  /* Writes vx, vy, vyaw when they change, at most 10 times a second; the
   * final value (e.g. the zero on release) always goes out. */
  function joySend(now) {
    var c = joyCommand(), bytes = c.map(centredByte), key = bytes.join(','), r = (meta && meta.ranges) || {};
    $('joy-out').textContent = 'vx ' + fix(c[0] * (r.vx_mm_s || 0), 0) + ' mm/s, vy ' + fix(c[1] * (r.vy_mm_s || 0), 0) +
      ' mm/s, yaw ' + fix(c[2] * (r.vyaw_deg_s || 0), 0) + ' deg/s';
    if (key === joy.sent) { return; }
    if (!now && performance.now() - joy.lastSend < 100) {
      if (!joy.timer) { joy.timer = setTimeout(function () { joy.timer = null; joySend(true); }, 100); }
      return;
    }
    joy.sent = key; joy.lastSend = performance.now();
    writeRegs([['vx', bytes[0]], ['vy', bytes[1]], ['vyaw', bytes[2]]]);
  }

  function drawJoystick() {
    var w = joyCanvas.width, r = w / 2 - 14, c = w / 2;
    joyCtx.clearRect(0, 0, w, w);
    joyCtx.strokeStyle = '#2d333d'; joyCtx.lineWidth = 1;
    joyCtx.beginPath(); joyCtx.arc(c, c, r, 0, 2 * Math.PI); joyCtx.moveTo(c - r, c); joyCtx.lineTo(c + r, c);
    joyCtx.moveTo(c, c - r); joyCtx.lineTo(c, c + r); joyCtx.stroke();
    joyCtx.fillStyle = (joy.x || joy.y || joy.side) ? '#4fb3ff' : '#3a4352';
    joyCtx.beginPath(); joyCtx.arc(c + joy.x * r, c - joy.y * r, 14, 0, 2 * Math.PI); joyCtx.fill();
  }

  function joyFromEvent(clientX, clientY) {
    var rect = joyCanvas.getBoundingClientRect(), r = rect.width / 2 - 14;
    var x = (clientX - rect.left - rect.width / 2) / r, y = -(clientY - rect.top - rect.height / 2) / r;
    var n = Math.hypot(x, y);
    if (n > 1) { x /= n; y /= n; }
    joySet(x, y, joy.side, false);
  }

  var joyDragging = false;
  joyCanvas.addEventListener('mousedown', function (e) { joyDragging = true; joyFromEvent(e.clientX, e.clientY); e.preventDefault(); });
  window.addEventListener('mousemove', function (e) { if (joyDragging) { joyFromEvent(e.clientX, e.clientY); } });
  window.addEventListener('mouseup', function () { if (joyDragging) { joyDragging = false; joySet(0, 0, joy.side, true); } });
  joyCanvas.addEventListener('touchstart', function (e) { joyFromEvent(e.touches[0].clientX, e.touches[0].clientY); e.preventDefault(); }, { passive: false });
  joyCanvas.addEventListener('touchmove', function (e) { joyFromEvent(e.touches[0].clientX, e.touches[0].clientY); e.preventDefault(); }, { passive: false });
  joyCanvas.addEventListener('touchend', function (e) { joySet(0, 0, joy.side, true); e.preventDefault(); }, { passive: false });

  var KEYMAP = { ArrowUp: 'f', KeyW: 'f', ArrowDown: 'b', KeyS: 'b', ArrowLeft: 'l', KeyA: 'l',
                 ArrowRight: 'r', KeyD: 'r', KeyQ: 'sl', KeyE: 'sr' };

  function typing(e) { var t = e.target.tagName; return t === 'INPUT' || t === 'SELECT' || t === 'TEXTAREA'; }

  function keysToJoy() {
    joySet((keys.r ? 1 : 0) - (keys.l ? 1 : 0), (keys.f ? 1 : 0) - (keys.b ? 1 : 0),
           (keys.sr ? 1 : 0) - (keys.sl ? 1 : 0), false);
  }

  window.addEventListener('keydown', function (e) {
    var k = KEYMAP[e.code];
    if (typing(e) && e.target.type !== 'checkbox') { return; }
    if (e.code === 'Space') { keys = {}; joySet(0, 0, 0, true); e.preventDefault(); return; }
    if (!k || e.repeat) { if (k) { e.preventDefault(); } return; }
    keys[k] = true; keysToJoy(); e.preventDefault();
  });
  window.addEventListener('keyup', function (e) {
    var k = KEYMAP[e.code];
    if (k && keys[k]) { delete keys[k]; keysToJoy(); if (!Object.keys(keys).length) { joySend(true); } }
  });
  window.addEventListener('blur', function () { if (Object.keys(keys).length) { keys = {}; joySet(0, 0, 0, true); } });
  $('joy-scale').addEventListener('input', function () { $('joy-scale-v').textContent = $('joy-scale').value + ' %'; joySend(false); });
  $('joy-x').addEventListener('change', function () { joySend(true); });

  /* ------------------------------------------------------------ emulator inputs */

  var inputStatus = $('input-status');

  function sendTilt() {
    postJson('input', { ground_tilt: { roll_deg: +$('in-roll').value, pitch_deg: +$('in-pitch').value } }, inputStatus);
  }

  [['in-roll', ' deg', 1], ['in-pitch', ' deg', 1], ['in-batt', ' %', 0]].forEach(function (d) {
    var el = $(d[0]), t = null;
    el.addEventListener('input', function () {
      inputBusyUntil[d[0]] = performance.now() + 1500;
      $(d[0] + '-v').textContent = fix(+el.value, d[2]) + d[1];
      if (t) { return; }
      t = setTimeout(function () {
        t = null;
        if (d[0] === 'in-batt') { postJson('input', { battery_pct: +el.value }, inputStatus); } else { sendTilt(); }
      }, 120);
    });
  });

  document.querySelectorAll('button[data-push]').forEach(function (b) {
    b.addEventListener('click', function () {
      var rp = b.dataset.push.split(',').map(Number);
      postJson('input', { push: { roll_deg: rp[0], pitch_deg: rp[1] } }, inputStatus);
    });
  });

  /* ------------------------------------------------------------ start */

  buildRegmap();
  buildJoints();
  drawJoystick();
  setConnected(false);
  connect();
  requestAnimationFrame(animate);
}());
