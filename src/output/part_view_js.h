// The JavaScript of report.html's 3D view of a part (part_view_html.h), on three.js and its
// OrbitControls (inlined by the page before it). One function, peensimPartView(element, data),
// draws one part: its triangles coloured by the chosen field, a colour bar with the target marked,
// and under it what a click (or a pick by triangle) finds there.
//
// Data (JSON, typed arrays as base64 of little-endian bytes): positions (float32, mm, xyz per
// vertex), indices (uint32, 3 per triangle shown), source (uint32 per triangle shown: the part's
// triangle), region (int32 per triangle shown, -1: none), fields [{name, label, unit, values
// (float32 per triangle shown; NaN: none), lo, hi, target|null, digits, categorical}],
// regions [{name, forecast}], shown (the field drawn first), instances (names of copies shown side
// by side, a sweep's variants) with instance (uint32 per triangle shown: its copy) and offsets (mm,
// each copy's shift along x: a picked point is given in the part's own frame). A field may have
// clipped (values above hi: its bar says >=) and grey (what its grey triangles are).
//
// A test hook: report.html#pick=V:T[:C] picks triangle T (the part's numbering; of copy C) of view V once the
// page is drawn, as a click on it would (the camera moved just outside it, looking at it along its
// normal, the ray cast from the middle of the view), and writes what it found into the view's
// info element as data-* attributes; data-lit-pixels counts the pixels the part covers.
#pragma once

namespace peensim {

inline constexpr const char* kPartViewJs = R"JS(
(function () {
  'use strict';
  function bytes(b64) {
    var s = atob(b64), u = new Uint8Array(s.length);
    for (var i = 0; i < s.length; i++) u[i] = s.charCodeAt(i);
    return u.buffer;
  }
  // viridis, 9 stops
  var ramp = [[0.267,0.005,0.329],[0.283,0.141,0.458],[0.254,0.265,0.530],[0.207,0.372,0.553],[0.164,0.471,0.558],
              [0.128,0.567,0.551],[0.135,0.659,0.518],[0.267,0.749,0.441],[0.478,0.821,0.318],[0.741,0.873,0.150],[0.993,0.906,0.144]];
  // tab20: twenty distinguishable colours (a gear's teeth are 20 regions)
  var categories = [[0.12,0.47,0.71],[0.68,0.78,0.91],[1.0,0.5,0.05],[1.0,0.73,0.47],[0.17,0.63,0.17],[0.6,0.87,0.54],
                    [0.84,0.15,0.16],[1.0,0.6,0.59],[0.58,0.4,0.74],[0.77,0.69,0.84],[0.55,0.34,0.29],[0.77,0.61,0.58],
                    [0.89,0.47,0.76],[0.97,0.71,0.82],[0.5,0.5,0.5],[0.78,0.78,0.78],[0.74,0.74,0.13],[0.86,0.86,0.55],
                    [0.09,0.75,0.81],[0.62,0.85,0.9]];
  var none = [0.62, 0.62, 0.62];
  function colour(field, x) {
    if (!isFinite(x)) return none;
    if (field.categorical) return x < 0 ? none : categories[Math.round(x) % categories.length];
    var t = field.hi > field.lo ? (x - field.lo) / (field.hi - field.lo) : 0.5;
    t = Math.min(1, Math.max(0, t)) * (ramp.length - 1);
    var i = Math.min(ramp.length - 2, Math.floor(t)), f = t - i;
    return [0, 1, 2].map(function (k) { return ramp[i][k] * (1 - f) + ramp[i + 1][k] * f; });
  }
  function css(c) { return 'rgb(' + c.map(function (v) { return Math.round(255 * v); }).join(',') + ')'; }
  function text(field, x, regions) {
    if (!isFinite(x)) return 'none';
    if (field.categorical) return x < 0 ? 'none' : regions[Math.round(x)].name;
    return x.toFixed(field.digits) + (field.unit ? ' ' + field.unit : '');
  }

  window.peensimPartView = function (root, data) {
    var positions = new Float32Array(bytes(data.positions));
    var indices = new Uint32Array(bytes(data.indices));
    var source = new Uint32Array(bytes(data.source));
    var instance = data.instances.length ? new Uint32Array(bytes(data.instance)) : null;
    var triangles = indices.length / 3;
    data.fields.forEach(function (f) { f.array = new Float32Array(bytes(f.values)); });

    var canvas = root.querySelector('canvas'), info = root.querySelector('.pv-info');
    var select = root.querySelector('select'), bar = root.querySelector('.pv-bar');
    data.fields.forEach(function (f, k) {
      var o = document.createElement('option');
      o.value = k; o.textContent = f.label;
      select.appendChild(o);
    });

    var renderer = new THREE.WebGLRenderer({canvas: canvas, antialias: true, preserveDrawingBuffer: true});
    renderer.setPixelRatio(window.devicePixelRatio || 1);
    renderer.setSize(canvas.clientWidth, canvas.clientHeight, false);
    renderer.setClearColor(0xffffff, 1);
    var scene = new THREE.Scene();
    var geometry = new THREE.BufferGeometry();
    var xyz = new Float32Array(triangles * 9), rgb = new Float32Array(triangles * 9);
    for (var t = 0; t < triangles; t++)
      for (var c = 0; c < 3; c++)
        for (var k = 0; k < 3; k++) xyz[9 * t + 3 * c + k] = positions[3 * indices[3 * t + c] + k];
    geometry.setAttribute('position', new THREE.BufferAttribute(xyz, 3));
    geometry.setAttribute('color', new THREE.BufferAttribute(rgb, 3));
    geometry.computeVertexNormals();
    geometry.computeBoundingSphere();
    var mesh = new THREE.Mesh(geometry, new THREE.MeshLambertMaterial({vertexColors: THREE.VertexColors, side: THREE.DoubleSide}));
    scene.add(mesh);
    var sphere = geometry.boundingSphere;
    var aspect = canvas.clientWidth / canvas.clientHeight, fov = 35;  // degrees, vertical
    var camera = new THREE.PerspectiveCamera(fov, aspect, sphere.radius * 0.001, sphere.radius * 20);
    // Far enough for the bounding sphere to fit the narrower of the two fields of view.
    var half = Math.min(fov / 2, Math.atan(Math.tan(fov * Math.PI / 360) * aspect) * 180 / Math.PI) * Math.PI / 180;
    var distance = 1.05 * sphere.radius / Math.sin(half);
    camera.position.copy(sphere.center).add((data.instances.length ? new THREE.Vector3(0.1, 0.75, 1.0) : new THREE.Vector3(1.2, 0.9, 1.6)).normalize().multiplyScalar(distance));
    camera.lookAt(sphere.center);
    scene.add(new THREE.AmbientLight(0xffffff, 0.45));
    var light = new THREE.DirectionalLight(0xffffff, 0.65);
    camera.add(light);
    scene.add(camera);
    var controls = new THREE.OrbitControls(camera, canvas);
    controls.target.copy(sphere.center);
    controls.update();
    function draw() { renderer.render(scene, camera); }
    controls.addEventListener('change', draw);

    var field = data.fields[0];
    function paint(k) {
      field = data.fields[k];
      for (var t = 0; t < triangles; t++) {
        var c = colour(field, field.array[t]);
        for (var v = 0; v < 3; v++) for (var j = 0; j < 3; j++) rgb[9 * t + 3 * v + j] = c[j];
      }
      geometry.attributes.color.needsUpdate = true;
      var legend = '';
      if (field.categorical) {
        legend = data.regions.map(function (r, i) {
          return '<span class="pv-key" style="background:' + css(categories[i % categories.length]) + '"></span>' + r.name;
        }).join(' ');
      } else {
        var stops = ramp.map(function (c, i) { return css(c) + ' ' + (100 * i / (ramp.length - 1)) + '%'; }).join(',');
        var mark = '';
        if (field.target !== null && field.hi > field.lo) {
          var at = 100 * (field.target - field.lo) / (field.hi - field.lo);
          mark = '<span class="pv-target" style="left:' + at + '%" title="target"></span>';
        }
        legend = '<span class="pv-lo">' + text(field, field.lo) + '</span><span class="pv-ramp" style="background:linear-gradient(to right,' +
                 stops + ')">' + mark + '</span><span class="pv-hi">' + (field.clipped ? '&ge; ' : '') + text(field, field.hi) + '</span>' +
                 (field.target !== null ? ' <span class="pv-note">| target ' + text(field, field.target) + '</span>' : '') +
                 ' <span class="pv-note">| grey: ' + (field.grey || 'no value') + '</span>';
      }
      bar.innerHTML = legend;
      draw();
    }
    select.addEventListener('change', function () { paint(+select.value); });

    var raycaster = new THREE.Raycaster();
    function show(hit) {
      if (!hit) { info.textContent = 'Nothing there: click on the part.'; info.removeAttribute('data-triangle'); return; }
      var t = hit.faceIndex, r = -1, rows = [];
      var p = hit.point.clone();
      if (instance) p.x -= data.offsets[instance[t]];  // the copies sit side by side: back to the part's frame
      data.fields.forEach(function (f) {
        if (f.categorical) { r = f.array[t]; return; }
        rows.push('<b>' + f.label + '</b>: ' + text(f, f.array[t]));
      });
      var region = r >= 0 ? data.regions[Math.round(r)] : null;
      var copy = instance ? data.instances[instance[t]] : '';
      info.innerHTML = (copy ? 'Variant <b>' + copy + '</b>: t' : 'T') + 'riangle ' + source[t] + ' at (' + p.x.toFixed(2) + ', ' + p.y.toFixed(2) + ', ' + p.z.toFixed(2) + ') mm in the part\'s frame' +
        (region ? ', region <b>' + region.name + '</b>' + (region.forecast ? ' (to the target: ' + region.forecast + ')' : '') : '') +
        '<br>' + rows.join('; ');
      info.setAttribute('data-triangle', source[t]);
      info.setAttribute('data-instance', copy);
      info.setAttribute('data-point', JSON.stringify([p.x, p.y, p.z]));
      info.setAttribute('data-region', region ? region.name : '');
      info.setAttribute('data-values', JSON.stringify(data.fields.map(function (f) { return f.array[t]; })));
      info.setAttribute('data-fields', JSON.stringify(data.fields.map(function (f) { return f.name; })));
    }
    function pick(ndc) {
      raycaster.setFromCamera(ndc, camera);
      var hits = raycaster.intersectObject(mesh);
      show(hits.length ? hits[0] : null);
    }
    var down = null;
    canvas.addEventListener('pointerdown', function (e) { down = [e.clientX, e.clientY]; });
    canvas.addEventListener('pointerup', function (e) {
      if (!down || Math.abs(e.clientX - down[0]) + Math.abs(e.clientY - down[1]) > 4) return;  // a drag turns the view
      var box = canvas.getBoundingClientRect();
      pick(new THREE.Vector2(2 * (e.clientX - box.left) / box.width - 1, 1 - 2 * (e.clientY - box.top) / box.height));
    });

    // Pick triangle `wanted` (the part's numbering; of copy `copy` side by side) as a click on it
    // would: from just outside it.
    this.pickTriangle = function (wanted, copy) {
      var t = -1;
      for (var i = 0; i < triangles; i++)
        if (source[i] === wanted && (!instance || instance[i] === (copy || 0))) { t = i; break; }
      if (t < 0) { show(null); return false; }
      var a = new THREE.Vector3().fromArray(xyz, 9 * t), b = new THREE.Vector3().fromArray(xyz, 9 * t + 3);
      var c = new THREE.Vector3().fromArray(xyz, 9 * t + 6);
      var centre = a.clone().add(b).add(c).multiplyScalar(1 / 3);
      var normal = b.clone().sub(a).cross(c.clone().sub(a)).normalize();
      var size = Math.max(a.distanceTo(b), b.distanceTo(c), c.distanceTo(a));
      camera.position.copy(centre).addScaledVector(normal, Math.max(size, 4 * camera.near));
      controls.target.copy(centre);
      controls.update();
      draw();
      pick(new THREE.Vector2(0, 0));
      return true;
    };
    this.litPixels = function () {
      var gl = renderer.getContext(), w = gl.drawingBufferWidth, h = gl.drawingBufferHeight;
      var px = new Uint8Array(w * h * 4), lit = 0;
      gl.readPixels(0, 0, w, h, gl.RGBA, gl.UNSIGNED_BYTE, px);
      for (var i = 0; i < px.length; i += 4) if (px[i] < 250 || px[i + 1] < 250 || px[i + 2] < 250) lit++;
      return lit;
    };
    var first = data.shown || 0;
    select.value = first;
    paint(first);
    info.setAttribute('data-lit-pixels', this.litPixels());
    info.textContent = 'Click on the part to read its values there. Drag to turn, wheel to zoom, right-drag to pan.';
  };

  window.addEventListener('load', function () {
    var views = [];
    document.querySelectorAll('.pv').forEach(function (root) {
      var data = JSON.parse(root.querySelector('script[type="application/json"]').textContent);
      try {
        views.push(new window.peensimPartView(root, data));
      } catch (e) {
        root.querySelector('.pv-info').textContent = 'The 3D view could not be drawn here (' + e.message + '): this browser may lack WebGL.';
        root.querySelector('.pv-info').setAttribute('data-error', e.message);
        views.push(null);
      }
    });
    var m = /pick=(\d+):(\d+)(?::(\d+))?/.exec(location.hash);
    if (m && views[+m[1]]) {
      var root = document.querySelectorAll('.pv')[+m[1]];
      root.querySelector('.pv-info').setAttribute('data-picked', views[+m[1]].pickTriangle(+m[2], +(m[3] || 0)) ? 'yes' : 'no');
    }
    document.body.setAttribute('data-views-ready', views.length);
  });
})();
)JS";

}  // namespace peensim
