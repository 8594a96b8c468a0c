// Render the equations pymdownx.arithmatex marks (generic mode: <span class="arithmatex">\(...\)</span>
// inline, <div class="arithmatex">\[...\]</div> displayed) with the KaTeX the site ships
// (docs/assets/katex). A formula KaTeX cannot parse stays as its TeX source, in red.
(function () {
  function render(root) {
    root.querySelectorAll(".arithmatex").forEach(function (el) {
      if (el.dataset.rendered) return;
      var tex = el.textContent.trim();
      var display = el.tagName === "DIV";
      tex = tex.replace(/^\\[\(\[]/, "").replace(/\\[\)\]]$/, "");
      try {
        katex.render(tex, el, { displayMode: display, throwOnError: true });
      } catch (error) {
        el.textContent = tex;
        el.style.color = "#c00";
        el.title = String(error);
      }
      el.dataset.rendered = "1";
    });
  }
  if (typeof document$ !== "undefined") {
    document$.subscribe(function () { render(document.body); });
  } else {
    document.addEventListener("DOMContentLoaded", function () { render(document.body); });
  }
})();
