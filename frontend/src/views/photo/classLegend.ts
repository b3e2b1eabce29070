// Under the photo while the masks are coloured by class: each class the scene holds with its
// colour, so "the green ones" can be read as chairs without hovering each mask.
import { el } from "../../dom";
import { classText } from "../../state/classNames";
import type { SceneSession } from "../../state/sceneSession";
import { classColours } from "../objectColors";
import { rgbCss } from "../rgb";
import { type MaskStyleSetting, maskStyle } from "./maskStyle";

/** The legend (hidden while colouring by object) and how to stop updating it. */
export function classLegend(
  session: SceneSession,
  setting: MaskStyleSetting = maskStyle,
): { element: HTMLElement; dispose: () => void } {
  const element = el("div", {
    className: "legend class-legend",
    testid: "class-legend",
    attrs: { "aria-label": "Mask colours by class" },
  });
  const draw = () => {
    const byClass = setting.get().colouring === "class";
    element.hidden = !byClass;
    if (!byClass) return;
    const counts = new Map<string, number>();
    for (const object of session.objects)
      counts.set(object.class, (counts.get(object.class) ?? 0) + 1);
    const classes = [...counts.keys()].sort((a, b) => classText(a).localeCompare(classText(b)));
    const colours = classColours(classes);
    element.replaceChildren(
      ...classes.map((cls) =>
        el(
          "span",
          { className: "legend-item", attrs: { "data-class": cls } },
          el("span", {
            className: "swatch",
            attrs: { style: `background: ${rgbCss(colours.get(cls) ?? [128, 128, 128])}` },
          }),
          `${classText(cls)} (${counts.get(cls)})`,
        ),
      ),
    );
  };
  draw();
  const stopStyle = setting.subscribe(draw);
  const stopSession = session.subscribe((change) => {
    if (change === "document") draw();
  });
  return {
    element,
    dispose: () => {
      stopStyle();
      stopSession();
    },
  };
}
