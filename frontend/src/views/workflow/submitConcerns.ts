// What a reviewer would send a scene back for in its supports, said before it is submitted:
// objects without a supporter, objects whose menus show a supporter the model suggests
// that nobody accepted (the stored one is what is submitted, not the suggestion), and
// people's labels the model is sure are something else (orange in the list: more often a
// slip than a discovery, so worth a second look, not a change).
import { plural, type SceneSession } from "../../state/sceneSession";
import { withoutSupporter } from "../../state/supportGraph";

type Supports = Pick<SceneSession, "objects" | "shown" | "displayed" | "doubtedLabels">;

const listed = (ids: string[], has: string) =>
  `${plural(ids.length, "object")} (${ids.join(", ")}) ${ids.length === 1 ? "has" : "have"} ${has}`;

/** One sentence per kind of unsettled support; none when every support is settled. */
export function unsettledSupports(session: Supports): string[] {
  const missing = withoutSupporter(session.objects, session.shown()).map((o) => o.id);
  const suggested = session.objects
    .filter((o) => session.displayed(o.id)?.suggested)
    .map((o) => o.id);
  const doubted = session.objects.filter((o) => session.doubtedLabels().has(o.id)).map((o) => o.id);
  return [
    ...(missing.length > 0 ? [listed(missing, "no supporter.")] : []),
    ...(suggested.length > 0
      ? [
          listed(
            suggested,
            "a supporter the model suggests and nobody accepted (dashed in the list): the " +
              "stored one is what is submitted.",
          ),
        ]
      : []),
    ...(doubted.length > 0
      ? [
          listed(
            doubted,
            "a supporter set by a person that the support model is sure is something else " +
              "(orange in the list): worth a second look.",
          ),
        ]
      : []),
  ];
}
