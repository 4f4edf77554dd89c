//! The report's own model as a control (`model.report = true`,
//! `docs/model.md`, "The report's model"): its Figs. 3 .. 7, 10 and 12 as
//! snapshots of the report's model in its own clock ([`ReportSnapshots`],
//! beside the corrected fig03 .. fig12), its Figs. 8 and 11 as its own tip
//! speeds ([`ReportTip`]), and its Fig. 9 with what each erratum changes
//! ([`ReportVmax`]). `fc_paper_figures::report_model`
//! makes the tables, its `plot` the drawings.

use fc_paper_figures::{plot, report_model, report_model_tip};

use crate::ctx::Ctx;
use crate::registry::{Figure, Make};

/// Snapshots of a report scene run in the report's model.
pub struct ReportSnapshots {
    pub title: &'static str,
    /// The corrected scene (fig03 .. fig07's).
    pub scene: &'static str,
    /// The report figure's time span, in its clock.
    pub t_report: f64,
}

impl Make for ReportSnapshots {
    fn scenes(&self) -> Vec<&'static str> {
        vec![self.scene]
    }

    /// `<id>.csv` and, if the figure lists it, `<id>-cases.csv`:
    /// [`report_model::snapshot_tables`].
    fn compute(&self, ctx: &Ctx, fig: &Figure) -> Result<Vec<String>, String> {
        let scene = &ctx.run(self.scene)?.scene;
        // A figure that lists `<id>-cases.csv` also has the pair of runs of
        // its stepper.
        let cases = fig.data.len() > 1;
        let tables = report_model::snapshot_tables(self.scene, scene, self.t_report, cases)?;
        ctx.write_tables(fig.id, &tables)
    }

    fn draw(&self, ctx: &Ctx, fig: &Figure) -> Result<Vec<String>, String> {
        ctx.draw(fig, |r, s| plot::report_model::snapshots(r, s, self.title))
    }
}

/// The report's Fig. 9 in its model, and a pair of runs per erratum.
pub struct ReportVmax {
    pub title: &'static str,
    /// The corrected scene of the spans (span-d3: n = 50, r = 0.0005).
    pub scene: &'static str,
    /// The report figure's time span, in its clock (12).
    pub t_report: f64,
}

impl Make for ReportVmax {
    fn scenes(&self) -> Vec<&'static str> {
        vec![self.scene, "horizontal-damped", "horizontal-undamped"]
    }

    /// `<id>.csv`: [`report_model::vmax`] at the scene's spans;
    /// `<id>-errata.csv`: [`report_model::errata`] of the scene (to the
    /// report's t = 12) and of the horizontal ones (to its t = 10);
    /// `<id>-errata-spans.csv`: [`report_model::errata_spans`], each
    /// erratum undone at each of the spans.
    fn compute(&self, ctx: &Ctx, fig: &Figure) -> Result<Vec<String>, String> {
        let base = &ctx.run(self.scene)?.scene;
        let csv = report_model::vmax(base, self.t_report)?;
        let run = |name| ctx.run(name).map(|r| &r.scene);
        let errata = report_model::errata(&[
            (self.scene, base, self.t_report),
            ("horizontal-damped", run("horizontal-damped")?, 10.0),
            ("horizontal-undamped", run("horizontal-undamped")?, 10.0),
        ])?;
        let spans = report_model::errata_spans(base, self.t_report)?;
        Ok(vec![
            ctx.write(&format!("{}.csv", fig.id), &csv)?,
            ctx.write(&format!("{}-errata.csv", fig.id), &errata)?,
            ctx.write(&format!("{}-errata-spans.csv", fig.id), &spans)?,
        ])
    }

    fn draw(&self, ctx: &Ctx, fig: &Figure) -> Result<Vec<String>, String> {
        let title = format!("{}: {}", fig.id, self.title);
        ctx.draw(fig, |r, s| plot::report_model::vmax(r, s, &title))
    }
}

/// The report's Fig. 8 or 11 in its model: its own tip speed and velocity
/// for `scenes`, and per scene the pair of runs of its stepper.
pub struct ReportTip {
    pub title: &'static str,
    pub scenes: &'static [&'static str],
    /// The report figure's time span, in its clock.
    pub t_report: f64,
}

impl Make for ReportTip {
    fn scenes(&self) -> Vec<&'static str> {
        self.scenes.to_vec()
    }

    /// `<id>.csv` and `<id>-cases.csv`: [`report_model_tip::tables`].
    fn compute(&self, ctx: &Ctx, fig: &Figure) -> Result<Vec<String>, String> {
        let scenes = (self.scenes.iter())
            .map(|&s| ctx.run(s).map(|r| (s, &r.scene)))
            .collect::<Result<Vec<_>, String>>()?;
        let (curves, cases) = report_model_tip::tables(&scenes, self.t_report)?;
        Ok(vec![
            ctx.write(&format!("{}.csv", fig.id), &curves)?,
            ctx.write(&format!("{}-cases.csv", fig.id), &cases)?,
        ])
    }

    fn draw(&self, ctx: &Ctx, fig: &Figure) -> Result<Vec<String>, String> {
        ctx.draw(fig, |r, s| plot::report_model::tip(r, s, self.title))
    }
}
