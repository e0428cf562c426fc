// The ppoe interactive view: a canvas-2D painter's-algorithm renderer of the frames'
// data (see ppoe-cli/src/picture/html.rs for the format). Orthographic camera looking
// at the view cube's centre from azimuth/elevation like matplotlib's view_init.
"use strict";
(function () {
  const D = JSON.parse(document.getElementById("ppoe-data").textContent);
  const canvas = document.getElementById("view");
  const ctx = canvas.getContext("2d");
  const slider = document.getElementById("slider");
  const playBtn = document.getElementById("play");
  const titleEl = document.getElementById("title");
  const rgb = (c, a) => a === undefined ? `rgb(${c[0]},${c[1]},${c[2]})` : `rgba(${c[0]},${c[1]},${c[2]},${a})`;
  const AXES = [[220, 30, 30], [20, 160, 40], [30, 60, 230]];
  const span = D.view.x[1] - D.view.x[0];
  const HOME = { az: 50, el: 5, zoom: 1, panX: 0, panY: 0 };
  let cam = Object.assign({}, HOME);
  // The address's fragment can set the start: "#paused&frame=10&az=140&el=30&zoom=1.5"
  // (for screenshots and links to a view).
  const hash = new URLSearchParams(location.hash.slice(1));
  const num = (k, lo, hi) => { const v = parseFloat(hash.get(k)); return Number.isFinite(v) ? Math.max(lo, Math.min(hi, v)) : null; };
  for (const [k, lo, hi] of [["az", -360, 360], ["el", -89, 89], ["zoom", 0.05, 20]]) { const v = num(k, lo, hi); if (v !== null) cam[k] = v; }
  let frame = Math.round(num("frame", 0, D.frames.length - 1) || 0);
  let playing = D.frames.length > 1 && !hash.has("paused"), last = 0;

  // Decode each frame's surface once: Int16 triples relative to the cube's centre.
  const surfaces = D.frames.map((f) => {
    const bin = atob(f.surface), n = bin.length / 2, out = new Array(n / 3);
    const dv = new DataView(new ArrayBuffer(bin.length));
    for (let i = 0; i < bin.length; i++) dv.setUint8(i, bin.charCodeAt(i));
    for (let i = 0; i < n / 3; i++) {
      const q = [0, 1, 2].map((k) => dv.getInt16(6 * i + 2 * k, true));
      out[i] = q.some((v) => v === -32768) ? null : q.map((v, k) => D.centre[k] + v * D.unit);
    }
    return out;
  });

  const sub = (a, b) => [a[0] - b[0], a[1] - b[1], a[2] - b[2]];
  const dot = (a, b) => a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
  const cross = (a, b) => [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]];
  const unit = (a) => { const n = Math.hypot(a[0], a[1], a[2]); return n > 0 ? a.map((x) => x / n) : null; };
  const apply = (m, p) => [0, 1, 2].map((i) => m[4 * i] * p[0] + m[4 * i + 1] * p[1] + m[4 * i + 2] * p[2] + m[4 * i + 3]);

  function camera() {
    const a = cam.az * Math.PI / 180, e = cam.el * Math.PI / 180;
    const t = [Math.cos(e) * Math.cos(a), Math.cos(e) * Math.sin(a), Math.sin(e)];
    const r = [-Math.sin(a), Math.cos(a), 0];
    const u = cross(t, r);
    const W = canvas.width, H = canvas.height;
    const s = cam.zoom * 0.8 * Math.min(W, H) / span;
    const light = unit([t[0] + 0.3 * r[0] + 0.9 * u[0], t[1] + 0.3 * r[1] + 0.9 * u[1], t[2] + 0.3 * r[2] + 0.9 * u[2]]);
    const proj = (p) => {
      const d = sub(p, D.centre);
      return [W / 2 + cam.panX + s * dot(d, r), H / 2 + cam.panY - s * dot(d, u), dot(d, t)];
    };
    return { t, r, u, proj, light };
  }

  function shade(c, l) {
    l = Math.max(0, Math.min(1, l));
    const k = 0.45 + 0.55 * l, h = 70 * l * l * l * l;
    return c.map((x) => Math.min(255, Math.round(x * k + h)));
  }

  // The floor grid (at z = 0 when the view holds it: the arm stands there) on round
  // multiples of a step, with ticks in metres along the two front edges, as in the PNG.
  function drawFloor(C) {
    const z = D.view.z[0] <= 0 && 0 <= D.view.z[1] ? 0 : D.view.z[0];
    const [x0, x1] = D.view.x, [y0, y1] = D.view.y;
    const raw = span / 6, mag = Math.pow(10, Math.floor(Math.log10(raw)));
    const step = [1, 2, 2.5, 5, 10].map((m) => m * mag).find((s) => s >= raw * 0.999);
    const digits = Math.max(0, -Math.floor(Math.log10(step) + 1e-9) + (step / mag === 2.5 ? 1 : 0));
    const ticks = (lo, hi) => { const t = []; for (let v = Math.ceil(lo / step - 1e-9) * step; v <= hi + 1e-9; v += step) t.push(v); return t; };
    const line = (a, b) => { const p = C.proj(a), q = C.proj(b); ctx.moveTo(p[0], p[1]); ctx.lineTo(q[0], q[1]); };
    ctx.beginPath();
    line([x0, y0, z], [x0, y1, z]); line([x1, y0, z], [x1, y1, z]);
    line([x0, y0, z], [x1, y0, z]); line([x0, y1, z], [x1, y1, z]);
    for (const x of ticks(x0, x1)) line([x, y0, z], [x, y1, z]);
    for (const y of ticks(y0, y1)) line([x0, y, z], [x1, y, z]);
    ctx.strokeStyle = "#d4d4dc"; ctx.lineWidth = 1; ctx.stroke();
    ctx.fillStyle = "#3c3c3c"; ctx.font = `${12 * (window.devicePixelRatio || 1)}px sans-serif`; ctx.textAlign = "center";
    const fmt = (v) => (Math.abs(v) < step / 2 ? 0 : v).toFixed(digits);
    // The x ticks along y = y_max, the y ticks along x = x_max; the corner (x_max, y_max)
    // is labelled once (by y).
    for (const x of ticks(x0, x1)) if (x < x1 - step / 2) { const p = C.proj([x, y1 + 0.05 * span, z]); ctx.fillText(fmt(x), p[0], p[1] + 10); }
    for (const y of ticks(y0, y1)) { const p = C.proj([x1 + 0.05 * span, y, z]); ctx.fillText(fmt(y), p[0], p[1] + 10); }
    const ax = C.proj([(x0 + x1) / 2, y1 + 0.15 * span, z]), ay = C.proj([x1 + 0.15 * span, (y0 + y1) / 2, z]);
    ctx.fillText("x [m]", ax[0], ax[1] + 14); ctx.fillText("y [m]", ay[0], ay[1] + 14);
  }

  function pushBodies(items, f, C) {
    for (const b of f.bodies) {
      const sh = D.shapes[b.s];
      const world = [];
      for (let i = 0; i < sh.v.length; i += 3) world.push(apply(b.m, [sh.v[i], sh.v[i + 1], sh.v[i + 2]]));
      for (const face of sh.f) {
        const pts = face.map((i) => world[i]);
        let n = [0, 0, 0];
        for (let i = 0; i < pts.length; i++) { const c = cross(pts[i], pts[(i + 1) % pts.length]); n = [n[0] + c[0], n[1] + c[1], n[2] + c[2]]; }
        n = unit(n);
        if (!n) continue;
        const facing = dot(n, C.t);
        if (sh.closed && facing <= 0) continue;
        if (facing < 0) n = n.map((x) => -x);
        const col = rgb(shade(b.rgb, dot(n, C.light)));
        items.push({ poly: pts.map(C.proj), fill: col, stroke: col });
      }
    }
  }

  function pushSurface(items, f, C, pts) {
    const nr = f.rows, nc = f.cols, col = D.colours.surface;
    let centre = [0, 0, 0], cnt = 0;
    for (const p of pts) if (p) { centre = [centre[0] + p[0], centre[1] + p[1], centre[2] + p[2]]; cnt++; }
    if (!cnt) return;
    centre = centre.map((x) => x / cnt);
    const L = unit([0.4, -0.3, 0.85]);
    for (let i = 0; i + 1 < nr; i++) {
      for (let j = 0; j + 1 < nc; j++) {
        const q = [pts[i * nc + j], pts[(i + 1) * nc + j], pts[(i + 1) * nc + j + 1], pts[i * nc + j + 1]];
        if (q.some((p) => !p)) continue;
        const n = unit(cross(sub(q[2], q[0]), sub(q[3], q[1])));
        if (!n) continue;
        const k = 0.55 + 0.45 * Math.abs(dot(n, L));
        const c = col.map((x) => Math.round(x * k));
        const wire = (i % 3 === 0) || (j % 3 === 0);
        items.push({ poly: q.map(C.proj), fill: rgb(c, 0.3), stroke: wire ? rgb(D.colours.wire, 0.35) : null });
      }
    }
  }

  function pushArm(items, f, C) {
    if (!f.bodies.length) {
      for (let i = 0; i + 1 < f.joints.length; i++) {
        items.push({ seg: [C.proj(f.joints[i]), C.proj(f.joints[i + 1])], col: rgb(D.colours.skeleton), w: 6 });
      }
    }
    const al = D.axisLen;
    for (const m of f.axes) {
      const o = [m[3], m[7], m[11]];
      for (let a = 0; a < 3; a++) {
        const tip = [o[0] + al * m[a], o[1] + al * m[4 + a], o[2] + al * m[8 + a]];
        items.push({ seg: [C.proj(o), C.proj(tip)], col: rgb(AXES[a]), w: 3 });
      }
    }
  }

  function depth(it) {
    const ps = it.poly || it.seg;
    return ps.reduce((s, p) => s + p[2], 0) / ps.length;
  }

  function draw() {
    const W = canvas.clientWidth, H = canvas.clientHeight, dpr = window.devicePixelRatio || 1;
    if (canvas.width !== Math.round(W * dpr) || canvas.height !== Math.round(H * dpr)) {
      canvas.width = Math.round(W * dpr); canvas.height = Math.round(H * dpr);
    }
    const C = camera(), f = D.frames[frame];
    ctx.fillStyle = "#fff";
    ctx.fillRect(0, 0, canvas.width, canvas.height);
    drawFloor(C);
    const items = [];
    pushBodies(items, f, C);
    pushSurface(items, f, C, surfaces[frame]);
    pushArm(items, f, C);
    items.sort((a, b) => depth(a) - depth(b));
    ctx.lineJoin = "round"; ctx.lineCap = "round";
    for (const it of items) {
      if (it.poly) {
        ctx.beginPath();
        it.poly.forEach((p, i) => i ? ctx.lineTo(p[0], p[1]) : ctx.moveTo(p[0], p[1]));
        ctx.closePath();
        ctx.fillStyle = it.fill; ctx.fill();
        if (it.stroke) { ctx.strokeStyle = it.stroke; ctx.lineWidth = 1; ctx.stroke(); }
      } else {
        ctx.beginPath(); ctx.moveTo(it.seg[0][0], it.seg[0][1]); ctx.lineTo(it.seg[1][0], it.seg[1][1]);
        ctx.strokeStyle = it.col; ctx.lineWidth = it.w * dpr; ctx.stroke();
      }
    }
    const marks = [[f.tool, "#000"], [f.mean2, rgb(D.colours.mean2)]];
    marks.forEach(([p, col], k) => {
      if (p.some((x) => x === null)) return;
      const q = C.proj(p);
      ctx.fillStyle = col; ctx.strokeStyle = col; ctx.lineWidth = 3 * dpr;
      if (k === 0) { ctx.beginPath(); ctx.arc(q[0], q[1], 4 * dpr, 0, 2 * Math.PI); ctx.fill(); }
      else { const d = 5 * dpr; ctx.beginPath(); ctx.moveTo(q[0] - d, q[1] - d); ctx.lineTo(q[0] + d, q[1] + d); ctx.moveTo(q[0] + d, q[1] - d); ctx.lineTo(q[0] - d, q[1] + d); ctx.stroke(); }
    });
    titleEl.textContent = f.title;
    slider.value = frame;
  }

  function legend() {
    const cols = [];
    for (const b of D.frames[0].bodies) if (cols.length < 3 && !cols.some((c) => c.join() === b.rgb.join())) cols.push(b.rgb);
    const arm = cols.length
      ? `<span class="sw" style="background:linear-gradient(90deg,${cols.map((c, i) => `${rgb(c)} ${100 * i / cols.length}%,${rgb(c)} ${100 * (i + 1) / cols.length}%`).join(",")})"></span>arm: the robot's visual geometry (URDF)`
      : `<span class="sw" style="background:${rgb(D.colours.skeleton)};height:6px"></span>arm: base, joints, tool`;
    const axes = `<span class="sw" style="background:linear-gradient(90deg,${rgb(AXES[0])} 33%,${rgb(AXES[1])} 33% 66%,${rgb(AXES[2])} 66%);height:4px"></span>frame axes x, y, z (base, joints, tool)`;
    const surf = `<span class="sw" style="background:${rgb(D.colours.surface, 0.45)};border:1px solid ${rgb(D.colours.wire)}"></span>`;
    const lbl = document.createElement("span");
    lbl.textContent = D.label;
    const el = document.getElementById("legend");
    el.innerHTML = `${arm}<br>${axes}<br>${surf}`;
    el.appendChild(lbl);
    el.insertAdjacentHTML("beforeend", `<br><span style="color:#000">●</span> <span style="color:${rgb(D.colours.mean2)}">✖</span>&nbsp; mean tool position · second-order mean`);
  }

  function tick(now) {
    if (playing && now - last >= D.delayMs) {
      last = now;
      frame = (frame + 1) % D.frames.length;
      draw();
    }
    requestAnimationFrame(tick);
  }

  let drag = null;
  canvas.addEventListener("contextmenu", (e) => e.preventDefault());
  canvas.addEventListener("mousedown", (e) => { drag = { x: e.clientX, y: e.clientY, pan: e.button === 2 || e.shiftKey }; canvas.style.cursor = "grabbing"; });
  window.addEventListener("mouseup", () => { drag = null; canvas.style.cursor = "grab"; });
  window.addEventListener("mousemove", (e) => {
    if (!drag) return;
    const dx = e.clientX - drag.x, dy = e.clientY - drag.y, dpr = window.devicePixelRatio || 1;
    drag.x = e.clientX; drag.y = e.clientY;
    if (drag.pan) { cam.panX += dx * dpr; cam.panY += dy * dpr; }
    else { cam.az -= dx * 0.4; cam.el = Math.max(-89, Math.min(89, cam.el + dy * 0.4)); }
    draw();
  });
  canvas.addEventListener("wheel", (e) => { e.preventDefault(); cam.zoom *= Math.exp(-e.deltaY * 0.0015); draw(); }, { passive: false });
  canvas.addEventListener("dblclick", () => { cam = Object.assign({}, HOME); draw(); });
  playBtn.addEventListener("click", () => { playing = !playing; playBtn.textContent = playing ? "pause" : "play"; });
  slider.max = D.frames.length - 1;
  slider.addEventListener("input", () => { frame = +slider.value; draw(); });
  window.addEventListener("resize", draw);
  if (!playing) playBtn.textContent = "play";
  legend();
  draw();
  requestAnimationFrame(tick);
})();
