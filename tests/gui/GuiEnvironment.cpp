#include "GuiEnvironment.h"

#include <QApplication>
#include <QSettings>
#include <QTest>
#include <QSurfaceFormat>
#include <QTemporaryDir>
#include <QVTKOpenGLNativeWidget.h>

#include "AppModes.h"
#include "NumericLocale.h"

namespace reamsim::ui::test {
namespace {

class GuiEnvironment : public ::testing::Environment {
 public:
  void SetUp() override {
    if (!haveDisplay()) return;
    qputenv("QT_QPA_PLATFORM", "xcb");
    QSurfaceFormat::setDefaultFormat(QVTKOpenGLNativeWidget::defaultFormat());
    static int argc = 1;
    static char name[] = "reamsim_gui_tests";
    static char* argv[] = {name, nullptr};
    app_ = std::make_unique<QApplication>(argc, argv);
    useCNumberFormats();  // as main() does
    QCoreApplication::setOrganizationName("ReamSimTests");
    QCoreApplication::setApplicationName("reamsim_gui_tests");
    settingsDir_ = std::make_unique<QTemporaryDir>();  // never the user's settings
    QSettings::setPath(QSettings::NativeFormat, QSettings::UserScope, settingsDir_->path());
  }
  void TearDown() override {
    settingsDir_.reset();
    app_.reset();
  }

 private:
  std::unique_ptr<QApplication> app_;
  std::unique_ptr<QTemporaryDir> settingsDir_;
};

const auto* const kEnvironment = ::testing::AddGlobalTestEnvironment(new GuiEnvironment);

}  // namespace

bool haveDisplay() { return !qEnvironmentVariableIsEmpty("DISPLAY"); }

GuiFixture::GuiFixture(const QString& pluginDir, bool loadDefault) {
  plugins = std::make_unique<PluginHost>();
  plugins->loadFrom(pluginDir);
  window = std::make_unique<MainWindow>(*plugins, false);
  window->resize(1100, 760);
  window->show();
  EXPECT_TRUE(waitExposed(*window, 10000));
  // Window shortcuts (the thesis keys) need an active window; without a window manager activation
  // is asynchronous, and under load the first key events could otherwise arrive before it.
  window->raise();
  window->activateWindow();
  EXPECT_TRUE(QTest::qWaitForWindowActive(window.get(), 10000));
  if (loadDefault) {
    EXPECT_TRUE(window->loadDefaultCase()) << window->lastError().toStdString();
    EXPECT_TRUE(session().waitIdle(60000));
  }
}

GuiFixture::~GuiFixture() {
  if (window) window->session().waitIdle(60000);
  window.reset();
}

}  // namespace reamsim::ui::test
