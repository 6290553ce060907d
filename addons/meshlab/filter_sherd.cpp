#include "filter_sherd.h"

#include <array>
#include <cmath>
#include <limits>
#include <optional>

#include <QFileInfo>
#include <QJsonArray>
#include <QJsonDocument>
#include <QJsonObject>
#include <QSaveFile>
#include <QStringList>

#include <vcg/complex/algorithms/update/bounding.h>
#include <vcg/complex/algorithms/update/position.h>

#include "sherd.hpp"

namespace {

// Where the axis of the analysis filters comes from.
enum AxisSource { AXIS_AUTOMATIC = 0, AXIS_LAYER_FRAME = 1 };

// How an orientation is applied to the layer.
enum ApplyTo { APPLY_TO_TRANSFORM = 0, APPLY_TO_VERTICES = 1 };

enum OrientMethod { ORIENT_AUTOMATIC = 0, ORIENT_THREE_POINTS = 1 };

const QStringList axisSources = {
	"Automatic (as Sherd: orient)",
	"Z axis of the layer (already oriented by Sherd: orient)"};
const QStringList applyToChoices = {"Layer transform", "Vertices"};
// How MeshLab shows one of the library's names: "mean_of_best" as "Mean of best".
QString label(const std::string& name)
{
	QString text = QString::fromStdString(name).replace('_', ' ');
	return text.left(1).toUpper() + text.mid(1);
}

// The library's names of a vocabulary (SHERD_VOCABULARY_*), each at the index of its
// value: a MeshLab enum parameter's index is the C value.
QStringList names(std::uint32_t vocabulary)
{
	QStringList listed;
	for (const std::string& name : sherd::names_by_value(vocabulary)) listed << QString::fromStdString(name);
	return listed;
}

// The labels of a vocabulary's enum parameter, index i for value i.
QStringList labels(std::uint32_t vocabulary)
{
	QStringList listed;
	for (const std::string& name : sherd::names_by_value(vocabulary)) listed << label(name);
	return listed;
}

// The drawing formats' labels: their names (the file extensions) in capitals.
QStringList formatLabels()
{
	QStringList listed;
	for (const QString& name : names(SHERD_VOCABULARY_FORMAT)) listed << name.toUpper();
	return listed;
}

QString axisSourceHelp()
{
	return "Automatic: the whole pipeline of <i>sherd orient</i> (repair, orientation from the "
	       "normals, refinement) on the layer as displayed. Z axis: the layer's frame is already "
	       "the oriented one (after <i>Sherd: orient</i>, including one from three points): the "
	       "axis is its z axis, rim up.";
}

// A MeshLab layer handed to sherd: its live vertices and faces, in the frame the layer
// is displayed in (its transform applied), and which MeshLab vertex each sherd vertex is.
struct LayerMesh {
	sherd::Mesh mesh;
	std::vector<CMeshO::VertexPointer> vertices;
	// The layer's matrix: `mesh` is in the frame it displays, its parameters in its own.
	Matrix44m transform;
};

vcg::Point3d transformPoint(const Matrix44m& m, const Point3m& p)
{
	vcg::Point3d out;
	for (int r = 0; r < 3; ++r)
		out[r] = double(m[r][0]) * p[0] + double(m[r][1]) * p[1] + double(m[r][2]) * p[2] + double(m[r][3]);
	return out;
}

LayerMesh layerMesh(MeshModel& model)
{
	CMeshO& cm = model.cm;
	std::vector<double> positions;
	std::vector<std::uint32_t> triangles;
	std::vector<CMeshO::VertexPointer> vertices;
	std::vector<std::uint32_t> index(cm.vert.size(), 0);
	positions.reserve(3 * cm.vn);
	vertices.reserve(cm.vn);
	for (std::size_t i = 0; i < cm.vert.size(); ++i) {
		CVertexO& v = cm.vert[i];
		if (v.IsD()) continue;
		index[i] = std::uint32_t(vertices.size());
		vertices.push_back(&v);
		vcg::Point3d p = transformPoint(cm.Tr, v.cP());
		positions.insert(positions.end(), {p[0], p[1], p[2]});
	}
	if (vertices.empty())
		throw MLException("Sherd: the layer '" + model.label() + "' has no vertices.");
	triangles.reserve(3 * cm.fn);
	for (CFaceO& f : cm.face) {
		if (f.IsD()) continue;
		for (int k = 0; k < 3; ++k)
			triangles.push_back(index[vcg::tri::Index(cm, f.V(k))]);
	}
	sherd::Mesh mesh = sherd::Mesh::from_arrays(positions, triangles);
	// A mesh's normals are recomputed by sherd from its faces; a point cloud has only
	// the scanner's. MeshLab gives every vertex a normal slot, all zero when the file
	// had none: then sherd is told there are none.
	if (triangles.empty() && model.hasDataMask(MeshModel::MM_VERTNORMAL)) {
		std::vector<double> normals;
		normals.reserve(positions.size());
		bool any = false;
		for (CVertexO* v : vertices) {
			vcg::Point3d n = transformPoint(cm.Tr, v->cN()) - transformPoint(cm.Tr, Point3m(0, 0, 0));
			any = any || n.SquaredNorm() > 0;
			normals.insert(normals.end(), {n[0], n[1], n[2]});
		}
		if (any) mesh.set_normals(normals);
	}
	if (model.hasDataMask(MeshModel::MM_VERTCOLOR)) {
		std::vector<std::uint8_t> rgba;
		rgba.reserve(4 * vertices.size());
		for (CVertexO* v : vertices)
			rgba.insert(rgba.end(), {v->cC()[0], v->cC()[1], v->cC()[2], v->cC()[3]});
		mesh.set_colors(rgba);
	}
	return LayerMesh{std::move(mesh), std::move(vertices), cm.Tr};
}

QString axisText(const SherdAxis& axis)
{
	return QString("point (%1, %2, %3) mm, direction (%4, %5, %6)")
		.arg(axis.point[0], 0, 'f', 3).arg(axis.point[1], 0, 'f', 3).arg(axis.point[2], 0, 'f', 3)
		.arg(axis.direction[0], 0, 'f', 5).arg(axis.direction[1], 0, 'f', 5).arg(axis.direction[2], 0, 'f', 5);
}

// A fragment sherd cannot orient: the filter fails with the library's reason and what to
// do; `rills` (from rillPoints) names three points on its longest wheel rill, if any, and
// `guess` the axis the library still found (its best guess, not trusted), if any.
MLException cannotOrient(const QString& reason, const QString& rills = QString(),
                         const std::optional<SherdAxis>& guess = std::nullopt)
{
	QString guessed = guess ? " Its best guess, not to be trusted for that reason: axis " + axisText(*guess) + "." : QString();
	return MLException("Sherd: this fragment does not determine its axis (" + reason +
	                   "). Orient it with Sherd: orient from three points picked on the rim or base" + rills +
	                   ", then use the layer's z axis." + guessed);
}

// The axis an automatic orientation still gives when it declines (its best guess), in the
// layer mesh's frame; none when it found no axis at all (its angle uncertainty infinite:
// the axis given is then only a vertical through the centroid).
std::optional<SherdAxis> bestGuess(const sherd::Orientation& found)
{
	if (found.report.angle_uncertainty_deg == std::numeric_limits<double>::infinity()) return std::nullopt;
	return found.axis;
}

// The pipeline record's best_guess (`record_json`): the axis it still found for a
// fragment it declined, in the layer mesh's frame; none when it found no axis.
std::optional<SherdAxis> recordBestGuess(const std::string& record_json)
{
	QJsonObject axis = QJsonDocument::fromJson(QByteArray::fromStdString(record_json))
	                       .object().value("best_guess").toObject().value("axis").toObject();
	QJsonArray point = axis.value("point").toArray();
	QJsonArray direction = axis.value("direction").toArray();
	if (point.size() != 3 || direction.size() != 3) return std::nullopt;
	return sherd::make_axis({point[0].toDouble(), point[1].toDouble(), point[2].toDouble()},
	                        {direction[0].toDouble(), direction[1].toDouble(), direction[2].toDouble()});
}

// The three points the library suggests on the longest wheel rill of a fragment it cannot
// orient (in the layer mesh's frame), as the three points method's parameters in the
// layer's own coordinates; empty when it traced no rill.
QString rillPoints(const LayerMesh& layer, const std::optional<std::array<double, 9>>& points)
{
	if (!points) return QString();
	Matrix44m back = vcg::Inverse(layer.transform);
	QStringList named;
	for (int i = 0; i < 3; ++i) {
		const double* p = points->data() + 3 * i;
		vcg::Point3d local = transformPoint(back, Point3m(Scalarm(p[0]), Scalarm(p[1]), Scalarm(p[2])));
		named << QString("point_%1 = (%2, %3, %4)").arg(i + 1).arg(local[0], 0, 'f', 3).arg(local[1], 0, 'f', 3)
		             .arg(local[2], 0, 'f', 3);
	}
	return ", for instance these on its longest wheel rill: " + named.join(", ");
}

// The pipeline record's manual_points_on_rill (`record_json`), if it gives them.
std::optional<std::array<double, 9>> recordRillPoints(const std::string& record_json)
{
	QJsonArray points = QJsonDocument::fromJson(QByteArray::fromStdString(record_json))
	                        .object().value("manual_points_on_rill").toArray();
	if (points.size() != 3) return std::nullopt;
	std::array<double, 9> values{};
	for (int i = 0; i < 3; ++i)
		for (int k = 0; k < 3; ++k) values[3 * i + k] = points[i].toArray()[k].toDouble();
	return values;
}

// The axis of the analysis filters, in the frame the layer is displayed in.
SherdAxis layerAxis(const LayerMesh& layer, int source)
{
	if (source == AXIS_LAYER_FRAME) return sherd::make_axis({0, 0, 0}, {0, 0, 1});
	if (source != AXIS_AUTOMATIC)
		throw MLException(QString("Sherd: axis source %1 is not one of 0 (automatic), 1 (layer frame).").arg(source));
	sherd::Analysis analysis = sherd::analyse(layer.mesh);
	if (analysis.status == SHERD_STATUS_NEEDS_MANUAL_ORIENTATION)
		throw cannotOrient(QString::fromStdString(analysis.reason), rillPoints(layer, recordRillPoints(analysis.record_json)),
		                   recordBestGuess(analysis.record_json));
	// The axis line is good, only which way is up is a guess: the measurements hold, a
	// drawing or the layer's frame may be upside down.
	if (analysis.status == SHERD_STATUS_SENSE_UNCERTAIN)
		qWarning("Sherd: the sense of the axis (base to rim) is uncertain: %s", analysis.reason.c_str());
	// Found but not pinned down: the axis is used (the best guess), and said to be one.
	QJsonObject record = QJsonDocument::fromJson(QByteArray::fromStdString(analysis.record_json)).object();
	if (record.value("status").toString() == names(SHERD_VOCABULARY_RECORD_STATUS).value(SHERD_RECORD_STATUS_AXIS_UNCERTAIN))
		qWarning("Sherd: the axis is not pinned down (%s): check it before using the figures.",
		         qUtf8Printable(record.value("reason").toString()));
	return analysis.axis;
}

Matrix44m toMatrix(const std::array<double, 16>& rowMajor)
{
	Matrix44m m;
	for (int r = 0; r < 4; ++r)
		for (int c = 0; c < 4; ++c)
			m[r][c] = Scalarm(rowMajor[4 * r + c]);
	return m;
}

// Moves the layer into sherd's oriented frame (axis on z, base down, the fragment on +x)
// through its transform, or for good through its vertices (MeshLab's "freeze").
void applyOrientation(MeshModel& model, const Matrix44m& oriented, int applyTo, unsigned int& postConditionMask)
{
	model.cm.Tr = oriented * model.cm.Tr;
	if (applyTo == APPLY_TO_VERTICES) {
		vcg::tri::UpdatePosition<CMeshO>::Matrix(model.cm, model.cm.Tr, true);
		vcg::tri::UpdateBounding<CMeshO>::Box(model.cm);
		model.cm.shot.ApplyRigidTransformation(model.cm.Tr);
		model.cm.Tr.SetIdentity();
		postConditionMask = MeshModel::MM_VERTCOORD | MeshModel::MM_VERTNORMAL | MeshModel::MM_FACENORMAL |
		                    MeshModel::MM_TRANSFMATRIX;
	}
	else {
		postConditionMask = MeshModel::MM_TRANSFMATRIX;
	}
}

int applyToParameter(const RichParameterList& parameters)
{
	int applyTo = parameters.getEnum("apply_to");
	if (applyTo != APPLY_TO_TRANSFORM && applyTo != APPLY_TO_VERTICES)
		throw MLException(QString("Sherd: apply_to %1 is not one of 0 (layer transform), 1 (vertices).").arg(applyTo));
	return applyTo;
}

QString matrixText(const Matrix44m& m)
{
	QString text;
	for (int r = 0; r < 4; ++r)
		text += QString("\n  %1 %2 %3 %4").arg(m[r][0], 10, 'f', 6).arg(m[r][1], 10, 'f', 6)
		            .arg(m[r][2], 10, 'f', 6).arg(m[r][3], 10, 'f', 6);
	return text;
}

// The section angle of the profile filters: NaN asks sherd for the most informative one.
double sectionAngleRad(const RichParameterList& parameters)
{
	if (parameters.getBool("most_informative_section")) return std::numeric_limits<double>::quiet_NaN();
	return double(parameters.getFloat("section_angle_deg")) * M_PI / 180.0;
}

std::array<double, 9> pickedPoints(const RichParameterList& parameters, const Matrix44m& transform)
{
	std::array<double, 9> points{};
	const char* names[3] = {"point_1", "point_2", "point_3"};
	for (int i = 0; i < 3; ++i) {
		// Points are picked on the layer as displayed: in its transformed frame.
		vcg::Point3d p = transformPoint(transform, parameters.getPoint3m(names[i]));
		for (int k = 0; k < 3; ++k) points[3 * i + k] = p[k];
	}
	return points;
}

std::map<std::string, QVariant> orient(MeshModel& model, const RichParameterList& parameters,
                                       unsigned int& postConditionMask, const FilterPlugin& logger)
{
	int applyTo = applyToParameter(parameters);
	LayerMesh layer = layerMesh(model);
	int method = parameters.getEnum("method");
	bool refine = parameters.getBool("refine");
	SherdAxis axis = sherd::make_axis({0, 0, 0}, {0, 0, 1});
	QString how;
	if (method == ORIENT_AUTOMATIC && refine) {
		axis = layerAxis(layer, AXIS_AUTOMATIC);
		how = "automatic orientation and refinement (as sherd orient)";
	}
	else if (method == ORIENT_AUTOMATIC || method == ORIENT_THREE_POINTS) {
		sherd::Orientation found = method == ORIENT_AUTOMATIC
			? sherd::orient_automatic(layer.mesh)
			: sherd::orient_from_three_points(layer.mesh, pickedPoints(parameters, model.cm.Tr));
		if (!found.oriented)
			throw cannotOrient(QString::fromStdString(found.reason),
			                   method == ORIENT_AUTOMATIC ? rillPoints(layer, sherd::points_on_longest_rill(layer.mesh, found.axis))
			                                              : QString(),
			                   method == ORIENT_AUTOMATIC ? bestGuess(found) : std::nullopt);
		axis = found.axis;
		how = method == ORIENT_AUTOMATIC ? "automatic orientation" : "three points";
		if (refine) {
			axis = sherd::refine(layer.mesh, axis).axis;
			how += " and refinement";
		}
	}
	else {
		throw MLException(QString("Sherd: method %1 is not one of 0 (automatic), 1 (three points).").arg(method));
	}
	Matrix44m oriented = toMatrix(layer.mesh.oriented_transform(axis));
	applyOrientation(model, oriented, applyTo, postConditionMask);
	logger.log("Sherd: orient (%s): axis %s", qUtf8Printable(how), qUtf8Printable(axisText(axis)));
	logger.log("Sherd: orienting transform%s", qUtf8Printable(matrixText(oriented)));
	return {};
}

std::map<std::string, QVariant> refine(MeshModel& model, const RichParameterList& parameters,
                                       unsigned int& postConditionMask, const FilterPlugin& logger)
{
	// Parameters are checked before any computation, so a mistake costs nothing.
	sherd::RefineOptions options(sherd_refine_options_new);
	sherd::check(sherd_refine_options_set_criterion(options.get(), std::uint32_t(parameters.getEnum("criterion"))));
	sherd::check(sherd_refine_options_set_surface(options.get(), std::uint32_t(parameters.getEnum("surface"))));
	int sections = parameters.getInt("section_count");
	if (sections < 0) throw MLException(QString("Sherd: section_count %1 is negative (0 lets sherd choose).").arg(sections));
	sherd::check(sherd_refine_options_set_section_count(options.get(), std::size_t(sections)));
	sherd::check(sherd_refine_options_set_search_bound_deg(options.get(), double(parameters.getFloat("search_bound_deg"))));
	int meanCount = parameters.getInt("pareto_mean_count");
	if (meanCount < 0) throw MLException(QString("Sherd: pareto_mean_count %1 is negative.").arg(meanCount));
	sherd::check(sherd_refine_options_set_pareto_choice(options.get(), std::uint32_t(parameters.getEnum("pareto_choice")),
	                                                    std::size_t(meanCount)));
	sherd::check(sherd_refine_options_set_edge(options.get(), std::uint32_t(parameters.getEnum("edge"))));
	sherd::check(sherd_refine_options_set_tangent_tolerance_mm(options.get(), double(parameters.getFloat("tangent_tolerance_mm"))));
	int minPoints = parameters.getInt("pareto_min_points");
	if (minPoints < 0) throw MLException(QString("Sherd: pareto_min_points %1 is negative.").arg(minPoints));
	sherd::check(sherd_refine_options_set_pareto_section_limits(options.get(), std::size_t(minPoints),
	                                                            double(parameters.getFloat("pareto_min_arc_deg"))));
	sherd::check(sherd_refine_options_set_circle_fit(options.get(), std::uint32_t(parameters.getEnum("circle_fit"))));
	// Each form of the profile criterion has its own parameter; the form chosen takes its own.
	std::uint32_t profileMethod = std::uint32_t(parameters.getEnum("profile_method"));
	double profileParameter = profileMethod == SHERD_PROFILE_METHOD_REFERENCE ? double(parameters.getInt("profile_sections"))
		: profileMethod == SHERD_PROFILE_METHOD_POLYNOMIAL ? double(parameters.getInt("profile_degree"))
		: double(parameters.getFloat("profile_knot_spacing_mm"));
	sherd::check(sherd_refine_options_set_profile_method(options.get(), profileMethod, profileParameter));
	QString plotPath = parameters.getSaveFileName("pareto_plot");
	if (!plotPath.isEmpty() && parameters.getEnum("criterion") != SHERD_CRITERION_PARETO)
		throw MLException("Sherd: pareto_plot draws the Pareto criterion's front: choose the Pareto criterion or leave "
		                  "the plot's file empty.");
	int applyTo = applyToParameter(parameters);
	LayerMesh layer = layerMesh(model);
	SherdAxis start = sherd::make_axis({0, 0, 0}, {0, 0, 1});
	if (parameters.getEnum("start_axis") == AXIS_AUTOMATIC) {
		sherd::Orientation found = sherd::orient_automatic(layer.mesh);
		if (!found.oriented)
			throw cannotOrient(QString::fromStdString(found.reason), QString(), bestGuess(found));
		start = found.axis;
	}
	else if (parameters.getEnum("start_axis") != AXIS_LAYER_FRAME) {
		throw MLException(QString("Sherd: start_axis %1 is not one of 0 (automatic), 1 (layer frame).")
		                      .arg(parameters.getEnum("start_axis")));
	}
	SherdRefinement* handle = nullptr;
	sherd::check(sherd_refine(layer.mesh.get(), &start, options.get(), &handle));
	SherdAxis axis = sherd::make_axis({0, 0, 0}, {0, 0, 1});
	SherdRefineReport report{};
	report.size = sizeof report;
	SherdStatus axisStatus = sherd_refinement_axis(handle, &axis);
	SherdStatus reportStatus = axisStatus == SHERD_STATUS_OK ? sherd_refinement_report(handle, &report) : axisStatus;
	SherdBuffer* plot = nullptr;
	SherdStatus plotStatus = reportStatus == SHERD_STATUS_OK && !plotPath.isEmpty()
		? sherd_refinement_pareto_plot_svg(handle, &plot) : reportStatus;
	sherd_refinement_free(handle);
	sherd::check(reportStatus);
	if (!plotPath.isEmpty()) {
		sherd::check(plotStatus);
		std::string svg = sherd::take_buffer(plot);
		// QSaveFile writes beside the target and renames on commit: no half-written plot.
		QSaveFile file(plotPath);
		if (!file.open(QIODevice::WriteOnly) || file.write(svg.data(), qint64(svg.size())) != qint64(svg.size()) ||
		    !file.commit())
			throw MLException(QString("Sherd: cannot write the Pareto plot %1: %2").arg(plotPath, file.errorString()));
		logger.log("Sherd: Pareto front plotted in %s", qUtf8Printable(plotPath));
	}
	Matrix44m oriented = toMatrix(layer.mesh.oriented_transform(axis));
	applyOrientation(model, oriented, applyTo, postConditionMask);
	logger.log("Sherd: refine (%s on %s, %zu sections): tilt %.3f deg, shift %.3f mm, residual %.4f -> %.4f mm",
	           qUtf8Printable(names(SHERD_VOCABULARY_CRITERION).value(int(report.criterion))),
	           qUtf8Printable(names(SHERD_VOCABULARY_SURFACE).value(int(report.surface))),
	           report.section_count, report.tilt_deg, report.shift_mm, report.start_residual_mm, report.residual_mm);
	logger.log("Sherd: refined axis %s", qUtf8Printable(axisText(axis)));
	if (report.flagged)
		logger.log("Sherd: the skins barely fix the refined axis's position; the measure filter's intervals say how far off it may be.");
	return {{"tilt_deg", report.tilt_deg}, {"shift_mm", report.shift_mm}, {"residual_mm", report.residual_mm}};
}

QString figure(double value, const char* unit, int decimals = 1)
{
	if (std::isnan(value)) return "not determined";
	return QString("%1 %2").arg(value, 0, 'f', decimals).arg(unit);
}

QString interval(const double bounds[2], const char* unit)
{
	if (std::isnan(bounds[0]) || std::isnan(bounds[1])) return QString();
	return QString(" (interval %1 to %2 %3)").arg(bounds[0], 0, 'f', 1).arg(bounds[1], 0, 'f', 1).arg(unit);
}

std::map<std::string, QVariant> measure(MeshModel& model, const RichParameterList& parameters,
                                        const FilterPlugin& logger)
{
	int samples = parameters.getInt("bootstrap_samples");
	if (samples < 0) throw MLException(QString("Sherd: bootstrap_samples %1 is negative.").arg(samples));
	sherd::MeasureOptions options(sherd_measure_options_new);
	sherd::check(sherd_measure_options_set_bootstrap_samples(options.get(), std::size_t(samples)));
	sherd::check(sherd_measure_options_set_confidence(options.get(), double(parameters.getFloat("confidence"))));
	LayerMesh layer = layerMesh(model);
	SherdAxis axis = layerAxis(layer, parameters.getEnum("axis"));
	SherdMeasurements m{};
	m.size = sizeof m;
	sherd::check(sherd_measure(layer.mesh.get(), &axis, options.get(), &m, nullptr));
	logger.log("Sherd: measure '%s'", qUtf8Printable(model.label()));
	logger.log("Sherd: rim diameter %s%s", qUtf8Printable(figure(m.rim_diameter_mm, "mm")),
	           qUtf8Printable(interval(m.rim_diameter_interval_mm, "mm")));
	logger.log("Sherd: base diameter %s%s", qUtf8Printable(figure(m.base_diameter_mm, "mm")),
	           qUtf8Printable(interval(m.base_diameter_interval_mm, "mm")));
	logger.log("Sherd: sector angle %s (%s of the circumference)", qUtf8Printable(figure(m.sector_angle_deg, "deg")),
	           qUtf8Printable(figure(m.sector_percent, "%")));
	logger.log("Sherd: height %s", qUtf8Printable(figure(m.height_mm, "mm")));
	logger.log("Sherd: wall thickness %s", qUtf8Printable(figure(m.wall_thickness_mm, "mm", 2)));
	logger.log("Sherd: capacity %s", qUtf8Printable(figure(m.capacity_litres, "litres", 3)));
	if (m.axis_uncertain)
		logger.log("Sherd: the axis is uncertain: its 95%% intervals reach %.1f deg and %.1f mm of mean point distance; check it before using these figures.",
		           m.axis_angle_interval_deg[1], m.axis_distance_interval_mm[1]);
	return {
		{"rim_diameter_mm", m.rim_diameter_mm},
		{"base_diameter_mm", m.base_diameter_mm},
		{"sector_angle_deg", m.sector_angle_deg},
		{"sector_percent", m.sector_percent},
		{"height_mm", m.height_mm},
		{"wall_thickness_mm", m.wall_thickness_mm},
		{"capacity_litres", m.capacity_litres},
	};
}

/// The or of the C ABI bits whose check boxes are ticked.
// The check box of one bit of a bit vocabulary (styles, annotations): `prefix` and the
// library's name, "style_linear".
QString boxName(const char* prefix, const std::string& name)
{
	return QString(prefix) + QString::fromStdString(name);
}

// The or of the bits of `vocabulary` whose check boxes (`prefix` + name) are ticked.
std::uint32_t tickedBits(const RichParameterList& parameters, std::uint32_t vocabulary, const char* prefix)
{
	std::uint32_t bits = 0;
	for (const sherd::VocabularyEntry& entry : sherd::vocabulary(vocabulary))
		if (parameters.getBool(boxName(prefix, entry.name))) bits |= entry.value;
	return bits;
}

// A check box per bit of `vocabulary`, named `prefix` + the library's name, with the
// library's description; those in `ticked` are ticked by default.
void addBoxes(RichParameterList& list, std::uint32_t vocabulary, const char* prefix, const QString& labelPrefix,
              std::uint32_t ticked)
{
	for (const sherd::VocabularyEntry& entry : sherd::vocabulary(vocabulary))
		list.addParam(RichBool(boxName(prefix, entry.name), (ticked & entry.value) != 0,
		                       labelPrefix + (labelPrefix.isEmpty() ? label(entry.name) : label(entry.name).toLower()),
		                       QString::fromStdString(entry.description) + "."));
}

std::map<std::string, QVariant> draw(MeshModel& model, const RichParameterList& parameters,
                                     const FilterPlugin& logger)
{
	int format = parameters.getEnum("format");
	const QStringList formatExtensions = names(SHERD_VOCABULARY_FORMAT);
	const QStringList formats = formatLabels();
	if (format < 0 || format >= formats.size())
		throw MLException(QString("Sherd: format %1 is not one of 0 (%2) to %3 (%4).")
		                      .arg(format).arg(formats.first()).arg(formats.size() - 1).arg(formats.last()));
	QString path = parameters.getSaveFileName("file");
	if (path.isEmpty()) throw MLException("Sherd: no file to write the drawing to.");
	QString extension = QFileInfo(path).suffix().toLower();
	if (extension.isEmpty()) path += "." + formatExtensions[format];
	else if (extension != formatExtensions[format])
		throw MLException(QString("Sherd: the file %1 ends in .%2 but the format is %3.").arg(path, extension, formats[format]));
	std::uint32_t styles = tickedBits(parameters, SHERD_VOCABULARY_STYLE, "style_");
	// The annotations' check boxes: annotations_<name>, the names of `sherd draw --annotations`.
	std::uint32_t annotations = tickedBits(parameters, SHERD_VOCABULARY_ANNOTATION, "annotations_");
	int scale = parameters.getInt("scale_denominator");
	if (scale < 1) throw MLException(QString("Sherd: scale 1:%1 is not a scale (1 to 100).").arg(scale));

	LayerMesh layer = layerMesh(model);
	SherdAxis axis = layerAxis(layer, parameters.getEnum("axis"));
	sherd::DrawOptions options(sherd_draw_options_new);
	sherd::check(sherd_draw_options_set_style(options.get(), styles));
	sherd::check(sherd_draw_options_set_scale_denominator(options.get(), std::uint32_t(scale)));
	sherd::check(sherd_draw_options_set_dpi(options.get(), double(parameters.getFloat("dpi"))));
	sherd::check(sherd_draw_options_set_section_angle_rad(options.get(), sectionAngleRad(parameters)));
	// The enums' indices are the C ABI's values, which check them.
	sherd::check(sherd_draw_options_set_placement(options.get(), std::uint32_t(parameters.getEnum("placement"))));
	sherd::check(sherd_draw_options_set_section_fill(options.get(), std::uint32_t(parameters.getEnum("section_fill"))));
	sherd::check(sherd_draw_options_set_interior_view(options.get(), parameters.getBool("interior_view")));
	sherd::check(sherd_draw_options_set_prolongation(options.get(), parameters.getBool("prolongation")));
	sherd::check(sherd_draw_options_set_annotations(options.get(), annotations));
	QByteArray title = parameters.getString("title").toUtf8();
	if (!title.isEmpty()) sherd::check(sherd_draw_options_set_title(options.get(), title.constData()));
	SherdDrawing* drawing = nullptr;
	sherd::check(sherd_drawing_build(layer.mesh.get(), &axis, options.get(), &drawing));
	QByteArray file = QFile::encodeName(path);
	SherdStatus status = sherd_drawing_write(drawing, file.constData());
	sherd_drawing_free(drawing);
	sherd::check(status);
	logger.log("Sherd: drawing of '%s' written to %s", qUtf8Printable(model.label()), qUtf8Printable(path));
	return {};
}

std::map<std::string, QVariant> reconstruct(MeshDocument& document, MeshModel& model,
                                            const RichParameterList& parameters, const FilterPlugin& logger)
{
	int segments = parameters.getInt("segments");
	if (segments < 3) throw MLException(QString("Sherd: %1 segments cannot make a turn (at least 3).").arg(segments));
	LayerMesh layer = layerMesh(model);
	SherdAxis axis = layerAxis(layer, parameters.getEnum("axis"));
	sherd::Mesh vessel = sherd::reconstruct(layer.mesh, axis, sectionAngleRad(parameters), std::size_t(segments));
	std::vector<double> positions = vessel.positions();
	std::vector<std::uint32_t> triangles = vessel.triangles();
	// The reconstruction comes in the oriented frame; it is placed where the fragment is
	// displayed, so that the two overlap.
	Matrix44m back = vcg::Inverse(toMatrix(layer.mesh.oriented_transform(axis)));

	MeshModel* created = document.addNewMesh("", model.label() + " reconstruction", true);
	CMeshO& cm = created->cm;
	std::size_t vertexCount = positions.size() / 3, faceCount = triangles.size() / 3;
	vcg::tri::Allocator<CMeshO>::AddVertices(cm, vertexCount);
	for (std::size_t i = 0; i < vertexCount; ++i) {
		vcg::Point3d p = transformPoint(back, Point3m(Scalarm(positions[3 * i]), Scalarm(positions[3 * i + 1]),
		                                              Scalarm(positions[3 * i + 2])));
		cm.vert[i].P() = Point3m(Scalarm(p[0]), Scalarm(p[1]), Scalarm(p[2]));
	}
	vcg::tri::Allocator<CMeshO>::AddFaces(cm, faceCount);
	for (std::size_t f = 0; f < faceCount; ++f)
		for (int k = 0; k < 3; ++k) cm.face[f].V(k) = &cm.vert[triangles[3 * f + k]];
	created->updateBoxAndNormals();
	logger.log("Sherd: reconstruction of '%s': %zu vertices, %zu faces, %d segments", qUtf8Printable(model.label()),
	           vertexCount, faceCount, segments);
	return {};
}

std::map<std::string, QVariant> regularity(MeshModel& model, const RichParameterList& parameters,
                                           unsigned int& postConditionMask, const FilterPlugin& logger)
{
	int map = parameters.getEnum("map");
	if (map != SHERD_REGULARITY_AXIS_DISTANCE && map != SHERD_REGULARITY_IDEAL_VESSEL)
		throw MLException(QString("Sherd: map %1 is not one of 0 (distance to the axis), 1 (ideal vessel).").arg(map));
	LayerMesh layer = layerMesh(model);
	SherdAxis axis = layerAxis(layer, parameters.getEnum("axis"));
	sherd::Regularity painted = sherd::regularity(layer.mesh, axis, std::uint32_t(map), sectionAngleRad(parameters));
	model.updateDataMask(MeshModel::MM_VERTQUALITY | MeshModel::MM_VERTCOLOR);
	float low = std::numeric_limits<float>::infinity(), high = -low;
	for (std::size_t i = 0; i < layer.vertices.size(); ++i) {
		const std::uint8_t* rgba = &painted.rgba[4 * i];
		layer.vertices[i]->Q() = Scalarm(painted.values[i]);
		layer.vertices[i]->C() = vcg::Color4b(rgba[0], rgba[1], rgba[2], rgba[3]);
		if (std::isfinite(painted.values[i])) {
			low = std::min(low, painted.values[i]);
			high = std::max(high, painted.values[i]);
		}
	}
	postConditionMask = MeshModel::MM_VERTQUALITY | MeshModel::MM_VERTCOLOR;
	logger.log("Sherd: regularity of '%s' (%s) as vertex quality and colour: %.3f to %.3f mm (colour scale %.3f to %.3f mm)",
	           qUtf8Printable(model.label()), qUtf8Printable(names(SHERD_VOCABULARY_REGULARITY).value(map)), low, high,
	           painted.value_range[0], painted.value_range[1]);
	return {{"min_mm", double(low)}, {"max_mm", double(high)}};
}

void addSectionParameters(RichParameterList& list)
{
	list.addParam(RichBool("most_informative_section", true, "Most informative section",
	                       "Cut the profile where sherd finds it most informative (the tallest cut, away from "
	                       "the fractures); otherwise at the angle below."));
	list.addParam(RichFloat("section_angle_deg", 0, "Section angle (deg)",
	                        "Angle of the profile about the axis, degrees from the fragment's centroid, when the "
	                        "most informative section is not chosen."));
}

void addAxisParameter(RichParameterList& list, const char* name = "axis", const char* label = "Axis")
{
	list.addParam(RichEnum(name, AXIS_AUTOMATIC, axisSources, label, axisSourceHelp()));
}

void addApplyToParameter(RichParameterList& list)
{
	list.addParam(RichEnum("apply_to", APPLY_TO_TRANSFORM, applyToChoices, "Apply to",
	                       "Layer transform: the vertices stay as scanned and the layer's matrix moves them into "
	                       "the oriented frame. Vertices: the coordinates themselves are moved (the matrix is "
	                       "frozen), as for exporting the oriented scan."));
}

} // namespace

FilterSherdPlugin::FilterSherdPlugin()
{
	typeList = {FP_SHERD_ORIENT, FP_SHERD_REFINE, FP_SHERD_MEASURE, FP_SHERD_DRAW, FP_SHERD_RECONSTRUCT, FP_SHERD_REGULARITY};
	for (ActionIDType filter : typeList)
		actionList.push_back(new QAction(filterName(filter), this));
}

QString FilterSherdPlugin::pluginName() const { return "FilterSherd"; }

QString FilterSherdPlugin::vendor() const { return "sherd"; }

QString FilterSherdPlugin::filterName(ActionIDType filter) const
{
	switch (filter) {
	case FP_SHERD_ORIENT: return "Sherd: orient";
	case FP_SHERD_REFINE: return "Sherd: refine";
	case FP_SHERD_MEASURE: return "Sherd: measure";
	case FP_SHERD_DRAW: return "Sherd: draw";
	case FP_SHERD_RECONSTRUCT: return "Sherd: reconstruct";
	case FP_SHERD_REGULARITY: return "Sherd: regularity";
	}
	return QString();
}

QString FilterSherdPlugin::pythonFilterName(ActionIDType filter) const
{
	switch (filter) {
	case FP_SHERD_ORIENT: return "sherd_orient";
	case FP_SHERD_REFINE: return "sherd_refine";
	case FP_SHERD_MEASURE: return "sherd_measure";
	case FP_SHERD_DRAW: return "sherd_draw";
	case FP_SHERD_RECONSTRUCT: return "sherd_reconstruct";
	case FP_SHERD_REGULARITY: return "sherd_regularity";
	}
	return QString();
}

QString FilterSherdPlugin::filterInfo(ActionIDType filter) const
{
	const QString reference =
		"<br><br>Method: <i>Wilczek, Monna, Navarro, Chateau-Smith</i>, <b>\"A computer tool to identify best "
		"matches for pottery fragments\"</b>, Journal of Archaeological Science: Reports 2018. Computed by the "
		"sherd library " + QString(sherd_version()) + ".";
	switch (filter) {
	case FP_SHERD_ORIENT:
		return "Finds the rotation axis of a pottery sherd and moves the layer into the oriented frame: axis on z, "
		       "base down and rim up, the fragment on the +x side, as in an archaeological drawing. Automatic "
		       "orientation uses the surface normals (with refinement it is the whole <i>sherd orient</i> "
		       "pipeline); for fragments that do not determine their axis (flat base, near-spherical, tiny) give "
		       "three points picked on one horizontal feature (the rim's edge, a groove, the base's edge)." +
		       reference;
	case FP_SHERD_REFINE:
		return "Refines the axis with one of the paper's criteria (horizontal circles, their Pareto front, "
		       "vertical profile superposition, the tangent plane of a level rim or base) and moves the layer "
		       "into the refined oriented frame." + reference;
	case FP_SHERD_MEASURE:
		return "Measures the oriented fragment and writes to the log the rim and base diameters with their "
		       "intervals, the preserved sector angle, the height, the wall thickness and the capacity "
		       "(complete profiles only). Figures the fragment does not determine are reported as such." +
		       reference;
	case FP_SHERD_DRAW:
		return "Writes the archaeological drawing of the fragment (section and interior view left of the axis, "
		       "exterior view right, scale bar) as SVG, EPS, PDF or PNG, in the chosen styles, scale and "
		       "resolution." + reference;
	case FP_SHERD_RECONSTRUCT:
		return "Adds a new layer with the vessel reconstructed from the fragment: its profile section revolved "
		       "a full turn about the axis, a closed watertight mesh placed over the fragment." + reference;
	case FP_SHERD_REGULARITY:
		return "Paints the vessel's regularity on the fragment as vertex quality and vertex colour: the "
		       "distance of every vertex to the axis (one colour per horizontal band on a regular, well "
		       "oriented vessel), or its signed distance to the ideal vessel revolved from one profile "
		       "(decoration and traces of making stand out)." + reference;
	}
	return QString();
}

FilterPlugin::FilterClass FilterSherdPlugin::getClass(const QAction* action) const
{
	switch (ID(action)) {
	case FP_SHERD_ORIENT:
	case FP_SHERD_REFINE: return FilterPlugin::Normal;
	case FP_SHERD_MEASURE: return FilterPlugin::Measure;
	case FP_SHERD_DRAW: return FilterPlugin::Other;
	case FP_SHERD_RECONSTRUCT: return FilterPlugin::MeshCreation;
	case FP_SHERD_REGULARITY: return FilterClass(FilterPlugin::Quality | FilterPlugin::VertexColoring);
	}
	return FilterPlugin::Generic;
}

FilterPlugin::FilterArity FilterSherdPlugin::filterArity(const QAction*) const { return SINGLE_MESH; }

int FilterSherdPlugin::getPreConditions(const QAction*) const { return MeshModel::MM_VERTCOORD; }

int FilterSherdPlugin::postCondition(const QAction* action) const
{
	switch (ID(action)) {
	case FP_SHERD_ORIENT:
	case FP_SHERD_REFINE:
		return MeshModel::MM_TRANSFMATRIX | MeshModel::MM_VERTCOORD | MeshModel::MM_VERTNORMAL | MeshModel::MM_FACENORMAL;
	case FP_SHERD_REGULARITY: return MeshModel::MM_VERTQUALITY | MeshModel::MM_VERTCOLOR;
	}
	return MeshModel::MM_NONE;
}

RichParameterList FilterSherdPlugin::initParameterList(const QAction* action, const MeshModel& mesh)
{
	RichParameterList list;
	switch (ID(action)) {
	case FP_SHERD_ORIENT: {
		list.addParam(RichEnum("method", ORIENT_AUTOMATIC, {"Automatic", "Three points"}, "Method",
		                       "Automatic: from the surface normals. Three points: from three points picked on one "
		                       "horizontal feature (rim edge, groove, base edge), given below."));
		list.addParam(RichBool("refine", true, "Refine",
		                       "Refine the axis after orienting it (criterion chosen by sherd), as <i>sherd "
		                       "orient</i> does."));
		Point3m centre = mesh.cm.bbox.Center();
		list.addParam(RichPosition("point_1", centre, "Point 1", "First picked point (three points method)."));
		list.addParam(RichPosition("point_2", centre, "Point 2", "Second picked point (three points method)."));
		list.addParam(RichPosition("point_3", centre, "Point 3", "Third picked point (three points method)."));
		addApplyToParameter(list);
		break;
	}
	case FP_SHERD_REFINE:
		addAxisParameter(list, "start_axis", "Start axis");
		list.addParam(RichEnum("criterion", SHERD_CRITERION_AUTO, labels(SHERD_VOCABULARY_CRITERION), "Criterion",
		                       "Circles: radius variance of horizontal sections (Eq. 2). Pareto: circle centres "
		                       "and residuals (Eq. 3-4). Profile: superposition of vertical profiles (Eq. 5-6). "
		                       "Tangent: the plane of a level rim or base (Eq. 7). Auto: tangent when the "
		                       "fragment keeps a level rim or base, otherwise circles averaged with the profile "
		                       "where the two agree."));
		list.addParam(RichEnum("surface", SHERD_SURFACE_BOTH, labels(SHERD_VOCABULARY_SURFACE), "Surface",
		                       "The skin of the vessel the criterion looks at."));
		list.addParam(RichInt("section_count", 0, "Sections",
		                      "Number of horizontal sections; 0 lets sherd choose from the fragment's height."));
		list.addParam(RichFloat("search_bound_deg", 10, "Search bound (deg)",
		                        "Largest tilt from the start axis the search considers, degrees (above 0, at "
		                        "most 45)."));
		list.addParam(RichEnum("pareto_choice", SHERD_PARETO_CHOICE_KNEE, labels(SHERD_VOCABULARY_PARETO_CHOICE), "Pareto solution",
		                       "With the Pareto criterion, the solution of the front that becomes the axis: the "
		                       "knee (smallest product of the two costs), the best centre dispersion (Eq. 3), the "
		                       "best circle residual (Eq. 4), or the mean of the best few (below)."));
		list.addParam(RichInt("pareto_mean_count", 2, "Best averaged",
		                      "How many of the best solutions the mean takes (the original tool takes 2)."));
		list.addParam(RichEnum("edge", SHERD_EDGE_DETECT, labels(SHERD_VOCABULARY_EDGE), "Tangent plane's edge",
		                       "With the tangent or auto criterion: the rim, the base, or the one whose extremes "
		                       "are level."));
		list.addParam(RichSaveFile("pareto_plot", QString(), "*.svg", "Pareto plot",
		                           "With the Pareto criterion: where to write the front drawn as an SVG plot "
		                           "(centre dispersion against circle residual, the chosen solution circled); "
		                           "empty for none."));
		list.addParam(RichFloat("tangent_tolerance_mm", 3, "Tangent plane's epsilon (mm)",
		                        "Eq. 7's tolerance: a vertical section whose extreme lies farther than this below "
		                        "the rim's top (above the base's bottom) is taken for damaged and left out."));
		list.addParam(RichInt("pareto_min_points", 10, "Pareto: fewest points per section",
		                      "With the Pareto criterion: a horizontal section with fewer points is left out "
		                      "(at least 3: a circle needs three)."));
		list.addParam(RichFloat("pareto_min_arc_deg", 3, "Pareto: smallest arc (deg)",
		                        "With the Pareto criterion: a horizontal section spanning a smaller arc about the "
		                        "axis is left out (0 to 360)."));
		list.addParam(RichEnum("circle_fit", SHERD_CIRCLE_FIT_TAUBIN, labels(SHERD_VOCABULARY_CIRCLE_FIT), "Pareto: circle fit",
		                       "With the Pareto criterion: how each section's circle is fitted (Chernov): Taubin "
		                       "is nearly unbiased on short arcs, Kasa pulls them towards small circles, "
		                       "Geometric refines Taubin's circle by least squares."));
		list.addParam(RichEnum("profile_method", SHERD_PROFILE_METHOD_SPLINE, labels(SHERD_VOCABULARY_PROFILE_METHOD), "Profile: form",
		                       "With the profile criterion: the distance to the longest vertical section (Eq. 5), "
		                       "or the residuals of a profile r(z) fitted per skin (Eq. 6), a polynomial or a "
		                       "cubic spline (the default: it follows a lip a polynomial cannot)."));
		list.addParam(RichInt("profile_sections", 12, "Profile: vertical sections",
		                      "With the reference profile (Eq. 5): the number of vertical sections (2 to 1000)."));
		list.addParam(RichInt("profile_degree", 6, "Profile: polynomial degree",
		                      "With the polynomial profile (Eq. 6): its degree (1 to 20)."));
		list.addParam(RichFloat("profile_knot_spacing_mm", 1.5, "Profile: knot spacing (mm)",
		                        "With the spline profile (Eq. 6): the distance between its knots along the height "
		                        "(0.1 to 1000 mm)."));
		addApplyToParameter(list);
		break;
	case FP_SHERD_MEASURE:
		addAxisParameter(list);
		list.addParam(RichInt("bootstrap_samples", 20, "Bootstrap samples",
		                      "Resamples behind the intervals of the diameters (0: no intervals; more is slower)."));
		list.addParam(RichFloat("confidence", 0.95, "Confidence", "Confidence level of the intervals, in (0, 1)."));
		break;
	case FP_SHERD_DRAW: {
		// By default the drawing goes beside the scan it shows.
		QFileInfo scan(mesh.fullName());
		QString file = scan.completeBaseName().isEmpty()
			? QString("sherd_drawing.svg")
			: scan.absolutePath() + "/" + scan.completeBaseName() + "_drawing.svg";
		addAxisParameter(list);
		list.addParam(RichSaveFile("file", file, "*.svg", "File",
		                           "Where to write the drawing; its extension must match the format."));
		list.addParam(RichEnum("format", SHERD_FORMAT_SVG, formatLabels(), "Format",
		                       "SVG (layers editable in Inkscape or Illustrator), EPS, PDF or PNG."));
		// The library's default styles (sherd draw's), ticked.
		addBoxes(list, SHERD_VOCABULARY_STYLE, "style_", QString(), SHERD_STYLE_LIGHT | SHERD_STYLE_OCCLUSION);
		list.addParam(RichInt("scale_denominator", 1, "Scale 1:", "Publication scale 1:N (1 to 100; 1 is natural size)."));
		list.addParam(RichFloat("dpi", 300, "DPI", "Resolution of raster content and PNG output (10 to 4800)."));
		list.addParam(RichEnum("placement", SHERD_PLACEMENT_BESIDE, labels(SHERD_VOCABULARY_PLACEMENT), "Placement",
		                       "The views beside the axis, or the fragment at its true distance from it."));
		list.addParam(RichEnum("section_fill", SHERD_SECTION_FILL_BLACK, labels(SHERD_VOCABULARY_SECTION_FILL), "Section fill",
		                       "The section filled black (the usual convention) or hatched at 45 degrees."));
		list.addParam(RichBool("interior_view", true, "Interior view", "Draw the interior view between the section and the axis."));
		list.addParam(RichBool("prolongation", true, "Prolongation", "Prolong the outer profile, dashed, to the full diameter."));
		addBoxes(list, SHERD_VOCABULARY_ANNOTATION, "annotations_", "Annotate the ", 0);
		list.addParam(RichString("title", QString(), "Title", "A title (inventory number...) printed on the drawing."));
		addSectionParameters(list);
		break;
	}
	case FP_SHERD_RECONSTRUCT:
		addAxisParameter(list);
		list.addParam(RichInt("segments", 180, "Segments", "Steps of the revolution (at least 3; 180 is 2 degrees each)."));
		addSectionParameters(list);
		break;
	case FP_SHERD_REGULARITY:
		addAxisParameter(list);
		list.addParam(RichEnum("map", SHERD_REGULARITY_IDEAL_VESSEL, labels(SHERD_VOCABULARY_REGULARITY), "Map",
		                       "Distance to the axis (mm), or signed distance to the ideal vessel revolved from "
		                       "the section (mm, positive outside)."));
		addSectionParameters(list);
		break;
	default: wrongActionCalled(action);
	}
	return list;
}

std::map<std::string, QVariant> FilterSherdPlugin::applyFilter(
	const QAction* action,
	const RichParameterList& parameters,
	MeshDocument& document,
	unsigned int& postConditionMask,
	vcg::CallBackPos* progress)
{
	// Nothing may escape into MeshLab but its own exception type: the library's failures
	// (and anything unforeseen) become filter errors carrying their message.
	try {
		return runFilter(ID(action), parameters, document, postConditionMask, progress);
	}
	catch (const MLException&) {
		throw;
	}
	catch (const sherd::Error& error) {
		throw MLException(QString("Sherd: ") + QString::fromUtf8(error.what()));
	}
	catch (const std::exception& error) {
		throw MLException(QString("Sherd: unexpected error: ") + QString::fromUtf8(error.what()));
	}
}

std::map<std::string, QVariant> FilterSherdPlugin::runFilter(
	ActionIDType filter,
	const RichParameterList& parameters,
	MeshDocument& document,
	unsigned int& postConditionMask,
	vcg::CallBackPos* progress)
{
	MeshModel* model = document.mm();
	if (model == nullptr) throw MLException("Sherd: no current layer.");
	sherd::check_abi();
	if (progress) progress(0, qUtf8Printable(filterName(filter)));
	std::map<std::string, QVariant> result;
	switch (filter) {
	case FP_SHERD_ORIENT: result = orient(*model, parameters, postConditionMask, *this); break;
	case FP_SHERD_REFINE: result = refine(*model, parameters, postConditionMask, *this); break;
	case FP_SHERD_MEASURE: result = measure(*model, parameters, *this); break;
	case FP_SHERD_DRAW: result = draw(*model, parameters, *this); break;
	case FP_SHERD_RECONSTRUCT: result = reconstruct(document, *model, parameters, *this); break;
	case FP_SHERD_REGULARITY: result = regularity(*model, parameters, postConditionMask, *this); break;
	default: throw MLException(QString("Sherd: unknown filter %1.").arg(filter));
	}
	if (progress) progress(100, qUtf8Printable(filterName(filter)));
	return result;
}
