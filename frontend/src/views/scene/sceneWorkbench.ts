// The scene's workbench on one SceneSession: the photo with its overlays and tools, the 3D
// view, and the support editor with the workflow, save bar, suggestions and history; each
// mounted in its panel, in the order their keys and layers need.
import { el } from "../../dom";
import { mountBoxTool } from "../../editors/boxTool";
import { mountEdgeInfo } from "../../editors/edgeInfo";
import { mountLayoutEditing } from "../../editors/layoutEditor";
import { mountMaskTools } from "../../editors/maskTools";
import { changeClass, mountObjectShortcuts } from "../../editors/objectShortcuts";
import { SELECT_TOOL_ID } from "../../editors/photoTools";
import { mountSaveBar } from "../../editors/saveBar";
import { mountSupportEditor } from "../../editors/supportEditor";
import { mountSupportShortcuts } from "../../editors/supportShortcuts";
import { mountSupportSuggestions } from "../../inference/supportSuggestions";
import { getAuthor } from "../../state/author";
import { startAutosave } from "../../state/autosave";
import { ObjectEditor } from "../../state/objectEditor";
import type { SceneSession } from "../../state/sceneSession";
import { classLegend } from "../photo/classLegend";
import { arrowLegend } from "../photo/layerBar";
import { mountPhotoView } from "../photo/photoView";
import { mountPlacementNotice } from "../scene3d/placementNotice";
import { mountScene3dInset } from "../scene3d/scene3dInset";
import { mountScene3d } from "../scene3d/scene3dView";
import { mountWorkflowBar } from "../workflow/workflowBar";
import { fitPanelToWindow } from "./editorPanelFit";
import { mountObjectSuggestions } from "./objectSuggestions";
import { pipelineWarningsPanel } from "./pipelineWarnings";
import { readOnlyBanner } from "./readOnlyBanner";
import { mountRevisionHistory } from "./revisionHistory";

/** A panel with its heading; `hint`, how to work it, goes beside the heading (a line of the
 * panel's toolbar less, where it made the buttons wrap). */
function panel(title: string, className: string, testid: string, hint?: string) {
  const body = el("div", { className: "panel-body" });
  const heading = el("h2", { text: title });
  const element = el(
    "section",
    { className: `panel ${className}`, testid, attrs: { "aria-label": title } },
    hint
      ? el(
          "div",
          { className: "panel-heading" },
          heading,
          el("span", { className: "hint", text: hint }),
        )
      : heading,
    body,
  );
  return { element, body };
}

/**
 * Fill `content` with the session's panels; the functions that remove them go into `disposers`
 * as each is mounted (so a failure half-way leaves nothing that cannot be removed).
 */
export function mountSceneWorkbench(
  content: HTMLElement,
  session: SceneSession,
  disposers: (() => void)[],
): void {
  const photo = panel("Photo", "panel--photo", "photo-panel");
  const scene3d = panel(
    "3D scene",
    "panel--scene3d",
    "scene3d-panel",
    "Drag: orbit · right-drag: pan · scroll: zoom",
  );
  const editor = panel("Support relations", "panel--editor", "editor-panel");
  const saveBar = el("div", { className: "save-bar", testid: "save-bar" });
  const table = el("div", { className: "editor-table" });
  const suggestions = el("div");
  const history = el("div");
  const workflow = el("div");
  editor.body.append(workflow, saveBar, suggestions, table, history);
  const edgeInfo = el("div");
  // The legends last: the line about the selection belongs right under the photo.
  const classes = classLegend(session);
  disposers.push(classes.dispose);
  photo.element.append(edgeInfo, arrowLegend(), classes.element);
  const banner = readOnlyBanner(session);
  const warnings = pipelineWarningsPanel(session);
  // In the order Tab takes them; the page's grid puts the editor beside the photo.
  content.append(banner.element, warnings.element, photo.element, editor.element, scene3d.element);
  const objectEditor = new ObjectEditor(session);
  const photoView = mountPhotoView(photo.body, session, objectEditor);
  // Under the line about the selection, with the legends: how the photo is drawn.
  edgeInfo.after(photoView.viewOptions);
  disposers.push(
    () => objectEditor.dispose(),
    photoView.dispose,
    // after the photo view: it draws in its SVG
    mountObjectSuggestions(photo.body, session, objectEditor),
  );
  // A scene this person can only look at: the photo panel leaves out the layout buttons and
  // the drawing tools (greyed, they stood between a reviewer and the photo).
  const markViewOnly = () => photo.element.classList.toggle("is-view-only", session.viewOnly);
  markViewOnly();
  disposers.push(
    session.subscribe((change) => {
      if (change === "lock") markViewOnly();
    }),
  );
  const revisions = mountRevisionHistory(history, session, objectEditor);
  disposers.push(revisions.dispose);
  const layout = mountLayoutEditing(photo.element, photo.body, session);
  // Room corners and a photo tool would both take the photo's presses: editing the layout
  // puts the tool down (back to Select), and taking up a tool ends the layout editing.
  const stopLayoutTakesSelect = layout.draft.subscribe((change) => {
    if (change === "mode" && layout.draft.editing) photoView.tools.activate(SELECT_TOOL_ID);
  });
  const stopToolEndsLayout = photoView.tools.onChange((tool) => {
    if (tool.id !== SELECT_TOOL_ID && layout.draft.editing) layout.draft.setEditing(false);
  });
  disposers.push(
    stopLayoutTakesSelect,
    stopToolEndsLayout,
    layout.dispose,
    mountEdgeInfo(edgeInfo, session),
    mountSupportShortcuts(session),
    mountBoxTool(photoView.tools),
    mountObjectShortcuts(objectEditor, photoView.tools.host.svg),
    // after the support keys: the polygon's Backspace wins while a polygon is drawn
    mountMaskTools(photoView.tools),
    startAutosave(session, { author: getAuthor, otherSaving: () => objectEditor.busy }),
    mountScene3d(scene3d.body, session, layout.draft),
    // after the 3D view: it moves the view's viewport
    mountScene3dInset(scene3d.element, layout.draft),
    mountPlacementNotice(scene3d.element, scene3d.body, session),
    mountSaveBar(saveBar, session, objectEditor),
    mountSupportEditor(
      table,
      session,
      (id, anchor) => {
        const object = session.object(id);
        if (object) void changeClass(objectEditor, object, anchor.getBoundingClientRect());
      },
      objectEditor,
    ),
    mountSupportSuggestions(suggestions, table, session),
    mountWorkflowBar(workflow, session, revisions.showSince),
    banner.dispose,
    warnings.dispose,
    // after the panels above it are filled: they set its top
    fitPanelToWindow(editor.element),
  );
}
