#!/usr/bin/env node
// Validates glTF files with the Khronos glTF-Validator (npm package gltf-validator).
// Usage: node scripts/validate_gltf.js FILE.gltf|FILE.glb...
// The package is looked up in $IRAD_NPM_DIR/node_modules (default build/npm, where
// scripts/setup.sh installs it), else as usual (NODE_PATH). External resources are read from each file's folder. One line per file:
//   FILE: N error(s), W warning(s)[, first error CODE at POINTER]
// Exit code 1 when any file has errors (or cannot be validated), 2 on bad usage.
'use strict';
const fs = require('fs');
const path = require('path');

function loadValidator() {
  const dir = process.env.IRAD_NPM_DIR || path.join(__dirname, '..', 'build', 'npm');
  const local = path.join(dir, 'node_modules', 'gltf-validator');
  return require(fs.existsSync(local) ? local : 'gltf-validator');
}

function externalResources(file) {
  return (uri) => fs.promises.readFile(path.resolve(path.dirname(file), decodeURIComponent(uri)));
}

async function validate(validator, file) {
  const report = await validator.validateBytes(new Uint8Array(fs.readFileSync(file)), {
    uri: path.basename(file),
    externalResourceFunction: externalResources(file),
  });
  const n = report.issues.numErrors;
  const first = report.issues.messages.find((m) => m.severity === 0);
  const where = first ? `, first error ${first.code} at ${first.pointer || '(file)'}` : '';
  console.log(`${file}: ${n} error(s), ${report.issues.numWarnings} warning(s)${where}`);
  return n === 0;
}

async function main(files) {
  if (files.length === 0) {
    console.error('usage: node scripts/validate_gltf.js FILE.gltf|FILE.glb...');
    return 2;
  }
  const validator = loadValidator();
  let ok = true;
  for (const file of files) {
    try {
      ok = (await validate(validator, file)) && ok;
    } catch (e) {
      console.log(`${file}: cannot be validated: ${e}`);
      ok = false;
    }
  }
  return ok ? 0 : 1;
}

main(process.argv.slice(2)).then((code) => process.exit(code));
