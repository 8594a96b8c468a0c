// Renders every formula of the built site with the KaTeX the site ships, as the browser
// would (docs/assets/javascripts/katex.js), and prints those KaTeX cannot parse.
// Usage: node tests/katex_check.js SITE_DIR  (tests/test_docs.py runs it after a build).
const fs = require("fs");
const path = require("path");
const site = process.argv[2];
const katex = require(path.resolve(site, "assets/katex/katex.min.js"));
const entities = { "&lt;": "<", "&gt;": ">", "&amp;": "&", "&quot;": '"', "&#39;": "'" };
function pages(dir) {
  return fs.readdirSync(dir, { withFileTypes: true }).flatMap((e) => {
    const p = path.join(dir, e.name);
    return e.isDirectory() ? pages(p) : p.endsWith(".html") ? [p] : [];
  });
}
let count = 0;
const failed = [];
for (const page of pages(site)) {
  const html = fs.readFileSync(page, "utf8");
  const re = /<(span|div) class="arithmatex">([\s\S]*?)<\/\1>/g;
  let m;
  while ((m = re.exec(html))) {
    count++;
    const tex = m[2].replace(/&(lt|gt|amp|quot|#39);/g, (e) => entities[e]).trim()
      .replace(/^\\[([]/, "").replace(/\\[)\]]$/, "");
    try {
      katex.renderToString(tex, { displayMode: m[1] === "div", throwOnError: true });
    } catch (error) {
      failed.push(`${path.relative(site, page)}: ${String(error).slice(0, 200)}`);
    }
  }
}
console.log(JSON.stringify({ formulas: count, failed }));
