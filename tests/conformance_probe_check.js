#!/usr/bin/env node
// The probe repairs nothing (tests/conformance_probe.h): the Khronos glTF-Validator finds on each
// probed copy exactly the errors (code and pointer) of the file's report.
// Usage: node tests/conformance_probe_check.js SUITE PROBED_COPY
// PROBED_COPY: the folder test_conformance.cpp copied SUITE into and probed in place
// ($IRAD_CONFORMANCE_OUT). Files the probe left as they are (byte-identical) are skipped.
// Exit code 1 when a probed file's errors differ, outside the listed exceptions.
'use strict';
const fs = require('fs');
const path = require('path');

const dir = process.env.IRAD_NPM_DIR || path.join(__dirname, '..', 'build', 'npm');
const validator = require(path.join(dir, 'node_modules', 'gltf-validator'));

// Files whose report this validator (the npm package, offline) cannot reproduce, probe or not.
const exceptions = {
  'base/data/buffer/non_relative_uri.gltf': 'an http URI: no network here (IO_ERROR)',
  'ext/KHR_node_visibility/data/node/unexpected_extension.gltf':
    'reported by validator 2.0.0-dev.3.11; the npm package is 2.0.0-dev.3.10',
};

function files(root) {
  return fs.readdirSync(root, { withFileTypes: true }).flatMap((e) => {
    const p = path.join(root, e.name);
    if (e.isDirectory()) return files(p);
    return /\.(gltf|glb)$/.test(e.name) ? [p] : [];
  });
}

const errors = (messages) =>
  messages.filter((m) => m.severity === 0).map((m) => `${m.code}@${m.pointer || ''}`).sort().join(' ');

async function main([suite, probed]) {
  let checked = 0, bad = 0;
  for (const source of files(suite)) {
    const name = path.relative(suite, source).split(path.sep).join('/');
    const copy = path.join(probed, name);
    if (!fs.existsSync(copy) || fs.readFileSync(copy).equals(fs.readFileSync(source))) continue;
    if (name in exceptions) continue;
    const report = JSON.parse(fs.readFileSync(`${source}.report.json`, 'utf8'));
    const got = await validator.validateBytes(new Uint8Array(fs.readFileSync(copy)), {
      uri: path.basename(copy),
      externalResourceFunction: (uri) =>
        fs.promises.readFile(path.resolve(path.dirname(copy), decodeURIComponent(uri))),
    });
    ++checked;
    const want = errors(report.issues.messages), have = errors(got.issues.messages);
    if (want !== have) {
      ++bad;
      console.log(`${name}: the probe changed its errors\n  report: ${want}\n  probed: ${have}`);
    }
  }
  console.log(`conformance probe: ${checked} probed files checked, ${bad} with other errors`);
  return bad === 0 && checked > 0 ? 0 : 1;
}

main(process.argv.slice(2)).then((code) => process.exit(code));
