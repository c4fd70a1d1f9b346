// A table wider than a phone scrolls sideways in its wrapper: the wrapper takes the keyboard's
// focus (arrow keys scroll it) and says what it is (WCAG 2.1.1; axe "scrollable-region-focusable").
"use strict";
(function () {
  function label() {
    for (const w of document.querySelectorAll(".md-typeset__scrollwrap")) {
      if (w.hasAttribute("tabindex")) continue;
      w.tabIndex = 0;
      w.setAttribute("role", "region");
      w.setAttribute("aria-label", "table (scrolls sideways)");
    }
  }
  if (window.document$ && window.document$.subscribe) window.document$.subscribe(label);
  else document.addEventListener("DOMContentLoaded", label);
})();
