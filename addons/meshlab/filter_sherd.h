// sherd's filters for MeshLab: orient, refine, measure, draw, reconstruct and paint the
// regularity of pottery sherds. The plugin only converts between MeshLab's layers and
// sherd's C ABI (include/sherd.h through bindings/cpp/sherd.hpp); every computation is
// the library's.
#ifndef SHERD_MESHLAB_FILTER_SHERD_H
#define SHERD_MESHLAB_FILTER_SHERD_H

#include <common/plugins/interfaces/filter_plugin.h>

class FilterSherdPlugin : public QObject, public FilterPlugin
{
	Q_OBJECT
	MESHLAB_PLUGIN_IID_EXPORTER(FILTER_PLUGIN_IID)
	Q_INTERFACES(FilterPlugin)

public:
	enum {
		FP_SHERD_ORIENT,
		FP_SHERD_REFINE,
		FP_SHERD_MEASURE,
		FP_SHERD_DRAW,
		FP_SHERD_RECONSTRUCT,
		FP_SHERD_REGULARITY
	};

	FilterSherdPlugin();

	QString pluginName() const override;
	QString vendor() const override;
	QString filterName(ActionIDType filter) const override;
	QString pythonFilterName(ActionIDType filter) const override;
	QString filterInfo(ActionIDType filter) const override;
	FilterClass getClass(const QAction* action) const override;
	FilterArity filterArity(const QAction* action) const override;
	int getPreConditions(const QAction* action) const override;
	int postCondition(const QAction* action) const override;
	RichParameterList initParameterList(const QAction* action, const MeshModel& mesh) override;
	std::map<std::string, QVariant> applyFilter(
		const QAction* action,
		const RichParameterList& parameters,
		MeshDocument& document,
		unsigned int& postConditionMask,
		vcg::CallBackPos* progress) override;

private:
	std::map<std::string, QVariant> runFilter(
		ActionIDType filter,
		const RichParameterList& parameters,
		MeshDocument& document,
		unsigned int& postConditionMask,
		vcg::CallBackPos* progress);
};

#endif // SHERD_MESHLAB_FILTER_SHERD_H
