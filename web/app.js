// The page: the CL file and any pasted machines go into Emscripten's in-memory file system,
// clpc_post (web/clpc_web.cpp) posts and certifies as `clpc compile` does, and the program,
// the diagnostics (each one a link to its CL line), the certificate and the backplot come
// back from there. Nothing is sent anywhere.
//
// A scripted case for tests: index.html?case=URL&machine=NAME fetches URL (same origin),
// posts it, and sets <body data-state="done"> with the results in #gcode, #log, #certificate.
'use strict';

const $ = (id) => document.getElementById(id);
let clpc = null;            // the Emscripten module
let cl = null;              // {name, bytes} of the CL file
let machinesFile = '';      // '' or the path of the pasted machines in the module's file system

function setStatus(text, state) {
  $('status').textContent = text;
  if (state) document.body.dataset.state = state;
}

function listMachines() {
  const text = clpc.ccall('clpc_machines', 'string', ['string'], [machinesFile]);
  const [list, errors] = text.split('errors\n');
  const select = $('machine'), keep = select.value;
  select.textContent = '';
  for (const line of list.split('\n').filter(Boolean)) {
    const [name, description] = line.split('\t');
    const o = document.createElement('option');
    o.value = name;
    o.textContent = name + ' — ' + description;
    select.appendChild(o);
  }
  if ([...select.options].some((o) => o.value === keep)) select.value = keep;
  $('toml-errors').textContent = errors || '';
}

function showSource(text) {
  const pre = $('source');
  pre.textContent = '';
  text.split('\n').forEach((line, i) => {
    const s = document.createElement('span');
    s.dataset.n = i + 1;
    s.textContent = line;
    pre.appendChild(s);
  });
}

function goToLine(n) {
  const pre = $('source');
  for (const s of pre.querySelectorAll('.hit')) s.classList.remove('hit');
  const s = pre.children[n - 1];
  if (!s) return;
  s.classList.add('hit');
  pre.scrollTop = s.offsetTop - pre.offsetTop - pre.clientHeight / 3;
}

// clpc's standard error: "file:line:col: error: ..." lines (with the source line and caret
// after them) become list items that go to their line; the certificate line is shown apart.
function showLog(log) {
  $('log').textContent = log;
  const list = $('diagnostics');
  list.textContent = '';
  const cert = $('certificate');
  cert.textContent = '';
  cert.className = '';
  let item = null;
  for (const line of log.split('\n')) {
    const m = /^(.*?):(\d+):(\d+): (error|warning|note): (.*)$/.exec(line) || /^(.*?): (error|warning|note): (.*)$/.exec(line);
    if (/^clpc: (NOT )?certified /.test(line)) {
      cert.textContent = line;
      cert.className = line.startsWith('clpc: certified') ? 'ok' : 'bad';
      item = null;
    } else if (m) {
      item = document.createElement('li');
      item.className = m.length === 6 ? m[4] : m[2];
      item.textContent = line;
      if (m.length === 6) {
        const n = Number(m[2]);
        item.dataset.line = n;
        item.addEventListener('click', () => goToLine(n));
      }
      list.appendChild(item);
    } else if (/^clpc: /.test(line)) {
      item = null;  // the totals: in #log, not a diagnostic
    } else if (item && line) {
      item.textContent += '\n' + line;  // the source line and the caret
    }
  }
}

function post() {
  if (!cl) return;
  // In a folder of its own, named as they are, so the messages say "part.cls:12:1: error".
  try { clpc.FS.mkdir('/work'); } catch (e) { /* there already */ }
  clpc.FS.chdir('/work');
  const input = cl.name, base = cl.name.replace(/\.[^.]*$/, ''), svg = 'plot.svg';
  const output = base + '.nc' === input ? base + '-posted.nc' : base + '.nc';
  for (const f of [output, svg]) { try { clpc.FS.unlink(f); } catch (e) { /* none yet */ } }
  clpc.FS.writeFile(input, cl.bytes);
  const r = JSON.parse(clpc.ccall('clpc_post', 'string', ['string', 'string', 'string', 'string', 'string'],
                                  [input, $('machine').value, machinesFile, output, svg]));
  showLog(r.log);
  $('gcode').textContent = '';
  $('plot').textContent = '';
  $('download').hidden = true;
  if (r.ok) {
    const program = clpc.FS.readFile(output, { encoding: 'utf8' });
    $('gcode').textContent = program;
    const a = $('download');
    a.href = URL.createObjectURL(new Blob([program], { type: 'text/plain' }));
    a.download = output;
    a.hidden = false;
    try {
      const img = document.createElement('img');
      img.alt = 'backplot';
      img.src = URL.createObjectURL(new Blob([clpc.FS.readFile(svg)], { type: 'image/svg+xml' }));
      $('plot').appendChild(img);
    } catch (e) { /* no plot: the program stands */ }
  }
  setStatus(r.ok ? 'Posted ' + cl.name + ' for ' + $('machine').value : 'Not posted: see the diagnostics', 'done');
}

function takeFile(name, bytes) {
  cl = { name: name.replace(/[\/\\]/g, '_'), bytes };
  $('filename').textContent = name;
  $('cl-name').textContent = name;
  showSource(new TextDecoder('latin1').decode(bytes));
  $('post').disabled = !clpc;
}

async function scriptedCase(params) {
  const url = params.get('case');
  const response = await fetch(url);
  if (!response.ok) throw new Error('cannot fetch ' + url);
  takeFile(url.split('/').pop(), new Uint8Array(await response.arrayBuffer()));
  if (params.get('machine')) $('machine').value = params.get('machine');
  post();
}

function wire() {
  $('file').addEventListener('change', async (e) => {
    const f = e.target.files[0];
    if (f) takeFile(f.name, new Uint8Array(await f.arrayBuffer()));
  });
  $('post').addEventListener('click', post);
  $('use-toml').addEventListener('click', () => {
    const text = $('toml').value;
    machinesFile = text.trim() ? '/machines.toml' : '';
    if (machinesFile) clpc.FS.writeFile(machinesFile, text);
    listMachines();
  });
  document.addEventListener('dragover', (e) => { e.preventDefault(); document.body.classList.add('dragging'); });
  document.addEventListener('dragleave', () => document.body.classList.remove('dragging'));
  document.addEventListener('drop', async (e) => {
    e.preventDefault();
    document.body.classList.remove('dragging');
    const f = e.dataTransfer.files[0];
    if (f) takeFile(f.name, new Uint8Array(await f.arrayBuffer()));
  });
}

createClpc().then(async (module) => {
  clpc = module;
  listMachines();
  wire();
  $('post').disabled = !cl;
  setStatus('Ready: open or drop a CL file', 'ready');
  const params = new URLSearchParams(location.search);
  if (params.get('case')) await scriptedCase(params);
}).catch((e) => setStatus('clpc failed: ' + e, 'error'));
