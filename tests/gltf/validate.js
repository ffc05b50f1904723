// The Khronos glTF-Validator (npm gltf-validator) on a .glb file (ctest gltf_validator, through
// consumers.py). Fails on any error and on any warning not explained in EXPLAINED below; prints the
// validator's counts and every message.
// usage: node validate.js FILE.glb
// exit 0 valid, 1 invalid, 77 when the validator is not installed (consumers.py decides whether that skips)
'use strict';
const fs = require('fs');
const path = require('path');
const { execSync } = require('child_process');

// warnings that are expected, with the reason (none so far: every warning fails the test)
const EXPLAINED = {};

function loadValidator() {
  try {
    return require('gltf-validator');
  } catch (e) {
    // installed globally (scripts/install-deps.sh: npm install -g): Node does not search there by itself
    const root = execSync('npm root -g', { encoding: 'utf8' }).trim();
    return require(path.join(root, 'gltf-validator'));
  }
}

async function main() {
  const file = process.argv[2];
  let validator;
  try {
    validator = loadValidator();
  } catch (e) {
    console.log('MISSING: the npm package gltf-validator is not installed (npm install -g gltf-validator)');
    process.exit(77);
  }
  const bytes = new Uint8Array(fs.readFileSync(file));
  const report = await validator.validateBytes(bytes, { maxIssues: 0, uri: path.basename(file) });
  const is = report.issues;
  console.log(`glTF-Validator ${report.validatorVersion}: ${path.basename(file)} ${bytes.length} bytes: ` +
              `${is.numErrors} errors, ${is.numWarnings} warnings, ${is.numInfos} infos, ${is.numHints} hints`);
  const info = report.info || {};
  console.log(`generator "${info.generator}", ${info.drawCallCount} draw calls, ${info.totalVertexCount} vertices, ` +
              `${info.totalTriangleCount} triangles, ${info.animationCount} animations, ` +
              `extensions required: ${JSON.stringify(info.extensionsRequired || [])}`);
  let bad = 0;
  for (const m of is.messages) {
    const severity = ['error', 'warning', 'info', 'hint'][m.severity];
    const why = EXPLAINED[m.code];
    console.log(`  ${severity} ${m.code} at ${m.pointer || m.offset}: ${m.message}` + (why ? ` (explained: ${why})` : ''));
    if (m.severity === 0 || (m.severity === 1 && !why)) ++bad;
  }
  if (!String(info.generator).startsWith('rootsim-output')) {
    console.log('FAIL: asset.generator does not carry rootsim\'s signature');
    ++bad;
  }
  if (bad) {
    console.log(`FAIL: ${bad} errors or unexplained warnings`);
    process.exit(1);
  }
  console.log('valid');
}

main().catch((e) => {
  console.log('FAIL: ' + (e && e.stack ? e.stack : e));
  process.exit(1);
});
