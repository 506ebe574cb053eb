#!/usr/bin/env node
// An independent reader of `ferret validate --json`: Ajv (the npm JSON-schema
// validator, draft 2020-12) checks the reports of valid and invalid plans against
// docs/validate.schema.json, so the schema and the writer cannot drift apart with
// only ferret's own checker (tests/support/json_schema.hpp) looking.
// Exits 77 (ctest: skipped) when Ajv is not installed (scripts/install-deps puts it
// in build/node when Node.js and npm are there).
//   node validate_report_ajv.js FERRET_BINARY SOURCE_DIR NODE_MODULES_DIR
'use strict';
const { execFileSync } = require('child_process');
const fs = require('fs');
const path = require('path');

const [ferret, source, modules] = process.argv.slice(2);
let Ajv2020;
try {
  Ajv2020 = require(path.join(modules, 'ajv', 'dist', '2020')).default;
} catch (e) {
  console.log(`Ajv not found in ${modules}: skipped`);
  process.exit(77);
}

const schema = JSON.parse(fs.readFileSync(path.join(source, 'docs', 'validate.schema.json'), 'utf8'));
const ajv = new Ajv2020({ allErrors: true, strict: false });
const check = ajv.compile(schema);

const scratch = fs.mkdtempSync(path.join(require('os').tmpdir(), 'ferret-ajv-'));
const csv = path.join(scratch, 'fast.csv');
// 4 m in 1 s along y through the detour cellar: too fast for the miniUGV and into the block.
fs.writeFileSync(csv, 't,x,y,z,yaw\n0,10,4.5,0,-1.57\n1,10,0.5,0,-1.57\n');
const cases = [
  { args: ['--world', 'examples/scenarios/tether_detour.yaml', '--plan', 'examples/plans/detour_ugv.json'], verdict: 'valid' },
  { args: ['--world', 'examples/worlds/default.yaml', '--plan', 'examples/plans/approach_uav.json', '--robot', 'm100'], verdict: 'valid' },
  { args: ['--world', 'examples/scenarios/tether_detour.yaml', '--plan', csv, '--robot', 'miniugv'], verdict: 'invalid' },
  { args: ['--world', 'examples/worlds/default.yaml', '--plan', 'examples/plans/too_fast_uav.csv', '--robot', 'm100'], verdict: 'invalid' },
];

let passed = 0, failed = 0;
for (const c of cases) {
  let out;
  try {
    out = execFileSync(ferret, ['validate', ...c.args, '--json'], { cwd: source, encoding: 'utf8' });
  } catch (e) {
    if (e.status !== 1) throw e;  // 1: an invalid plan, still a report on stdout
    out = e.stdout;
  }
  const report = JSON.parse(out);
  const ok = check(report) && report.verdict === c.verdict &&
             (c.verdict === 'valid') === (report.violations.length === 0);
  if (ok) {
    passed++;
  } else {
    failed++;
    console.log(`FAIL ${c.args.join(' ')}: verdict ${report.verdict}, expected ${c.verdict}`);
    console.log(JSON.stringify(check.errors, null, 1));
  }
}
// A report the schema must reject: the check itself can fail.
const broken = JSON.parse(execFileSync(ferret, ['validate', ...cases[0].args, '--json'], { cwd: source, encoding: 'utf8' }));
delete broken.margins;
if (check(broken)) { failed++; console.log('FAIL a report without margins passed the schema'); } else passed++;

fs.rmSync(scratch, { recursive: true, force: true });
console.log(`${passed} passed, ${failed} failed`);
process.exit(failed ? 1 : 0);
